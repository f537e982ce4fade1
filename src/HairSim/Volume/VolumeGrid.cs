using System.Numerics;

namespace HairSim;

/// <summary>
/// The grid the volume system splats hair into: nodes at Origin + Cell·(i, j, k), fitted each frame to the bounds of the
/// live particles with one empty cell of margin on every side, so a particle's eight surrounding nodes always exist.
/// Geometry only; each implementation keeps its own node buffers.
/// </summary>
public sealed class VolumeGrid
{
    /// <summary>At most this many nodes (4 MB per float4 buffer): hair spread wider than this at the asked cell size gets larger cells.</summary>
    public const int MaxNodes = 1 << 18;

    public Vector3 Origin { get; private set; }
    public float Cell { get; private set; }
    public float InvCell { get; private set; }
    public int Nx { get; private set; }
    public int Ny { get; private set; }
    public int Nz { get; private set; }
    public int NodeCount => Nx * Ny * Nz;

    /// <summary>
    /// Fits the grid around [min, max] with cells of <paramref name="cell"/> metres, grown until the grid has at most
    /// <see cref="MaxNodes"/> nodes. False (grid unchanged) when the bounds are empty or not finite.
    /// </summary>
    public bool Fit(Vector3 min, Vector3 max, float cell)
    {
        if (!(min.X <= max.X && min.Y <= max.Y && min.Z <= max.Z) || !float.IsFinite(min.X + min.Y + min.Z + max.X + max.Y + max.Z)
            || !(cell > 0f) || !float.IsFinite(cell))
            return false;
        var extent = max - min;
        for (int grow = 0; grow < 64; grow++)
        {
            // Node 0 sits one cell below the minimum and the last node at least one cell above the maximum.
            long nx = (long)(extent.X / cell) + 3, ny = (long)(extent.Y / cell) + 3, nz = (long)(extent.Z / cell) + 3;
            if (nx * ny * nz <= MaxNodes)
            {
                Cell = cell; InvCell = 1f / cell;
                Origin = min - new Vector3(cell);
                Nx = (int)nx; Ny = (int)ny; Nz = (int)nz;
                return true;
            }
            cell *= 1.25f;
        }
        return false;
    }

    /// <summary>
    /// The cell holding a point: the index of its lower node and the position inside the cell (0 … 1 per axis), or −1
    /// for a non-finite point (skipped, so one broken particle cannot spread into its neighbours). Points outside the
    /// fitted bounds are clamped into the grid.
    /// </summary>
    public int Locate(float px, float py, float pz, out float fx, out float fy, out float fz)
    {
        fx = fy = fz = 0f;
        if (!float.IsFinite(px + py + pz)) return -1;
        float ux = Clamp((px - Origin.X) * InvCell, Nx - 1.001f);
        float uy = Clamp((py - Origin.Y) * InvCell, Ny - 1.001f);
        float uz = Clamp((pz - Origin.Z) * InvCell, Nz - 1.001f);
        int ix = (int)ux, iy = (int)uy, iz = (int)uz;
        fx = ux - ix; fy = uy - iy; fz = uz - iz;
        return ix + Nx * (iy + Ny * iz);
    }

    private static float Clamp(float u, float hi) => u >= 0f ? (u <= hi ? u : hi) : 0f;

    /// <summary>
    /// The median density the particles of the rest pose see, roots included (trilinear weights, particles per node,
    /// on a grid of <paramref name="cell"/> metres over the rest pose): what <see cref="VolumeSettings.Density"/> is a
    /// multiple of. 0 for a world without free particles. Runs after edits only (allocates).
    /// </summary>
    public static float RestDensity(HairWorld w, float cell)
    {
        var min = new Vector3(float.MaxValue); var max = new Vector3(float.MinValue);
        int count = 0;
        for (int s = 0; s < w.StrandCount; s++)
            for (int i = w.StrandFirst[s], e = i + w.StrandParticleCount[s]; i < e; i++)
            {
                var r = new Vector3(w.RestX[i], w.RestY[i], w.RestZ[i]);
                if (!float.IsFinite(r.X + r.Y + r.Z)) continue;
                min = Vector3.Min(min, r); max = Vector3.Max(max, r); count++;
            }
        var grid = new VolumeGrid();
        if (count == 0 || !grid.Fit(min, max, cell)) return 0f;
        var density = new float[grid.NodeCount];
        int sy = grid.Nx, sz = grid.Nx * grid.Ny;
        for (int s = 0; s < w.StrandCount; s++)
            for (int i = w.StrandFirst[s], e = i + w.StrandParticleCount[s]; i < e; i++)
            {
                int b = grid.Locate(w.RestX[i], w.RestY[i], w.RestZ[i], out float fx, out float fy, out float fz);
                if (b < 0) continue;
                for (int c = 0; c < 8; c++)
                    density[b + ((c & 1) != 0 ? 1 : 0) + ((c & 2) != 0 ? sy : 0) + ((c & 4) != 0 ? sz : 0)] += Weight(c, fx, fy, fz);
            }
        var seen = new float[count];
        int n = 0;
        for (int s = 0; s < w.StrandCount; s++)
            for (int i = w.StrandFirst[s], e = i + w.StrandParticleCount[s]; i < e; i++)
            {
                int b = grid.Locate(w.RestX[i], w.RestY[i], w.RestZ[i], out float fx, out float fy, out float fz);
                if (b < 0) continue;
                float d = 0f;
                for (int c = 0; c < 8; c++)
                    d += Weight(c, fx, fy, fz) * density[b + ((c & 1) != 0 ? 1 : 0) + ((c & 2) != 0 ? sy : 0) + ((c & 4) != 0 ? sz : 0)];
                seen[n++] = d;
            }
        if (n == 0) return 0f;
        Array.Sort(seen, 0, n);
        return seen[Math.Min(n - 1, n / 2)];
    }

    /// <summary>Trilinear weight of corner c (bit 0: +x, bit 1: +y, bit 2: +z) for a point at (fx, fy, fz) in its cell.</summary>
    public static float Weight(int c, float fx, float fy, float fz) =>
        ((c & 1) != 0 ? fx : 1f - fx) * ((c & 2) != 0 ? fy : 1f - fy) * ((c & 4) != 0 ? fz : 1f - fz);
}
