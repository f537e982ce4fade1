using System.Diagnostics;
using System.Numerics;

namespace HairSim.Meshes;

/// <summary>
/// A signed distance field baked from a closed triangle mesh on a regular grid (negative inside), for hair
/// collision: trilinear distance and its gradient anywhere in the grid. Exact distances are computed in a narrow
/// band of <see cref="BandCells"/> cells around the surface (each triangle visits only the cells near it); the sign
/// comes from the angle-weighted pseudo-normal of the closest feature (Bærentzen &amp; Aanæs 2005), so it is right at
/// edges and corners too. Beyond the band a chamfer distance continues the field (sign by flood fill from the grid's
/// border), so hair that got deep into the mesh in one substep still finds the way out.
/// </summary>
public sealed class SignedDistanceField
{
    public const int MaxCells = 64 * 1024 * 1024;
    public const int BandCells = 3;

    private readonly float[] _d;

    private SignedDistanceField(Vector3 origin, float cell, int nx, int ny, int nz, float[] d, TimeSpan bake)
    {
        Origin = origin; CellSize = cell; Nx = nx; Ny = ny; Nz = nz; _d = d; BakeTime = bake;
        InvCell = 1f / cell;
        _band = BandCells * cell;
        _hx = nx - 1; _hy = ny - 1; _hz = nz - 1;
        (Bricks, BricksX, BricksY) = BuildBricks(d, nx, ny, nz);
    }

    /// <summary>1 / <see cref="CellSize"/>: grid coordinates are (p − origin) · InvCell.</summary>
    internal readonly float InvCell;
    private readonly float _band, _hx, _hy, _hz;

    /// <summary>The distances, x fastest then y then z (not a copy: for the collision kernels).</summary>
    internal float[] Data => _d;

    /// <summary>Cells per brick edge, as a shift: a brick is 4 × 4 × 4 cells.</summary>
    internal const int BrickShift = 2;

    /// <summary>
    /// For each brick of 4 × 4 × 4 cells, a lower bound of the field anywhere in it: the least of its corner values,
    /// less a few float roundings (a trilinear value lies between its cell's corner values up to rounding). The
    /// collision kernels skip the eight-value sample of particles whose brick says they are far enough away.
    /// </summary>
    internal readonly float[] Bricks;
    internal readonly int BricksX, BricksY;

    private static (float[] Bricks, int Bx, int By) BuildBricks(float[] d, int nx, int ny, int nz)
    {
        const int B = 1 << BrickShift;
        int bx = (nx - 2) / B + 1, by = (ny - 2) / B + 1, bz = (nz - 2) / B + 1; // bricks over the cells 0 … n − 2
        var bricks = new float[bx * by * bz];
        Array.Fill(bricks, float.MaxValue);
        float largest = 0f;
        // Node (x, y, z) is a corner of the cells x − 1 and x along each axis: it bounds the bricks holding those cells.
        for (int z = 0; z < nz; z++)
        {
            int z0 = Math.Max(0, z - 1) >> BrickShift, z1 = Math.Min(nz - 2, z) >> BrickShift;
            for (int y = 0; y < ny; y++)
            {
                int y0 = Math.Max(0, y - 1) >> BrickShift, y1 = Math.Min(ny - 2, y) >> BrickShift;
                for (int x = 0; x < nx; x++)
                {
                    float v = d[x + nx * (y + ny * z)];
                    largest = MathF.Max(largest, MathF.Abs(v));
                    int x0 = Math.Max(0, x - 1) >> BrickShift, x1 = Math.Min(nx - 2, x) >> BrickShift;
                    for (int k = z0; k <= z1; k++)
                        for (int j = y0; j <= y1; j++)
                            for (int i = x0; i <= x1; i++)
                            {
                                ref float b = ref bricks[i + bx * (j + by * k)];
                                if (v < b) b = v;
                            }
                }
            }
        }
        // Three lerps, each within an ulp or so of the largest value it mixes: a margin far above that.
        float slack = 1e-5f * largest + 1e-9f;
        for (int i = 0; i < bricks.Length; i++) bricks[i] -= slack;
        return (bricks, bx, by);
    }

    /// <summary>The lower bound of the field in the brick holding grid cell (x, y, z).</summary>
    internal float BrickBound(int x, int y, int z) => Bricks[(x >> BrickShift) + BricksX * ((y >> BrickShift) + BricksY * (z >> BrickShift))];

    public Vector3 Origin { get; }
    public float CellSize { get; }
    public int Nx { get; }
    public int Ny { get; }
    public int Nz { get; }
    /// <summary>How long <see cref="Bake"/> took, the bricks of lower bounds included (zero for a stored field).</summary>
    public TimeSpan BakeTime { get; private set; }
    public float Band => BandCells * CellSize;
    public long CellCount => (long)Nx * Ny * Nz;

    /// <summary>
    /// Bakes the field with cubic cells of <paramref name="cellSize"/> metres (a quarter of the thinnest part to be
    /// felt is a good choice: 2.5 mm for 1 cm ears). The grid covers the mesh plus the band on every side.
    /// </summary>
    public static SignedDistanceField Bake(TriangleMesh mesh, float cellSize)
    {
        ArgumentNullException.ThrowIfNull(mesh);
        var size = mesh.BoundsMax - mesh.BoundsMin;
        if (!float.IsFinite(cellSize) || cellSize <= 0f) throw new ArgumentOutOfRangeException(nameof(cellSize), cellSize, "Cell size must be positive.");
        var clock = Stopwatch.StartNew();
        int pad = BandCells + 1;
        var origin = mesh.BoundsMin - new Vector3(pad * cellSize);
        long nx = (long)MathF.Ceiling(size.X / cellSize) + 2 * pad + 1, ny = (long)MathF.Ceiling(size.Y / cellSize) + 2 * pad + 1,
            nz = (long)MathF.Ceiling(size.Z / cellSize) + 2 * pad + 1;
        if (nx * ny * nz > MaxCells)
            throw new ArgumentOutOfRangeException(nameof(cellSize), cellSize, $"{nx}×{ny}×{nz} cells exceed {MaxCells:N0}: choose a larger cell size.");
        int Nx = (int)nx, Ny = (int)ny, Nz = (int)nz;
        // Each closed part (a head and separately modelled ears overlap) gets its own field; the union is their minimum.
        float[]? d = null;
        var weld = Weld(mesh.Positions);
        foreach (var part in Parts(mesh, weld))
        {
            var f = BakePart(part, weld, origin, cellSize, Nx, Ny, Nz);
            if (d == null) d = f;
            else for (int i = 0; i < d.Length; i++) d[i] = MathF.Min(d[i], f[i]);
        }
        var field = new SignedDistanceField(origin, cellSize, Nx, Ny, Nz, d!, TimeSpan.Zero);
        field.BakeTime = clock.Elapsed;
        return field;
    }

    private static float[] BakePart(TriangleMesh mesh, int[] weld, Vector3 origin, float cellSize, int Nx, int Ny, int Nz)
    {
        var pseudo = new PseudoNormals(mesh, weld);
        var d = new float[Nx * Ny * Nz];
        var sign = new sbyte[d.Length];
        Array.Fill(d, float.MaxValue);
        float band = BandCells * cellSize;

        // Narrow band: each triangle writes exact distances into the cells of its bounding box grown by the band.
        // Threads own slabs of z (every triangle is offered to the slabs it reaches), so no two write one cell.
        int slabs = Math.Min(Nz, Environment.ProcessorCount * 4);
        var bySlab = new List<int>[slabs];
        for (int k = 0; k < slabs; k++) bySlab[k] = new List<int>();
        for (int t = 0; t < mesh.TriangleCount; t++)
        {
            var (a, b, c) = mesh.Triangle(t);
            float zlo = MathF.Min(a.Z, MathF.Min(b.Z, c.Z)) - band - origin.Z, zhi = MathF.Max(a.Z, MathF.Max(b.Z, c.Z)) + band - origin.Z;
            int z0 = Math.Max(0, (int)MathF.Floor(zlo / cellSize)), z1 = Math.Min(Nz - 1, (int)MathF.Ceiling(zhi / cellSize));
            for (int k = (int)((long)z0 * slabs / Nz); k <= (int)((long)z1 * slabs / Nz) && k < slabs; k++) bySlab[k].Add(t);
        }
        Parallel.For(0, slabs, k =>
        {
            int zs = (int)(((long)k * Nz + slabs - 1) / slabs), ze = (int)(((long)(k + 1) * Nz + slabs - 1) / slabs) - 1;
            float band2 = band * band;
            foreach (int t in bySlab[k])
            {
                var (a, b, c) = mesh.Triangle(t);
                var normal = mesh.FaceNormal(t);
                var lo = Vector3.Min(a, Vector3.Min(b, c)) - new Vector3(band) - origin;
                var hi = Vector3.Max(a, Vector3.Max(b, c)) + new Vector3(band) - origin;
                int x0 = Math.Max(0, (int)MathF.Floor(lo.X / cellSize)), x1 = Math.Min(Nx - 1, (int)MathF.Ceiling(hi.X / cellSize));
                int y0 = Math.Max(0, (int)MathF.Floor(lo.Y / cellSize)), y1 = Math.Min(Ny - 1, (int)MathF.Ceiling(hi.Y / cellSize));
                int z0 = Math.Max(zs, (int)MathF.Floor(lo.Z / cellSize)), z1 = Math.Min(ze, (int)MathF.Ceiling(hi.Z / cellSize));
                for (int z = z0; z <= z1; z++)
                    for (int y = y0; y <= y1; y++)
                        for (int x = x0; x <= x1; x++)
                        {
                            var p = origin + new Vector3(x, y, z) * cellSize;
                            // Most of the grown box is farther than the band from the triangle's plane: skip those cells
                            // before the closest-point test (a degenerate triangle has no plane and is tested in full).
                            if (MathF.Abs(Vector3.Dot(p - a, normal)) > band) continue;
                            var q = ClosestOnTriangle(p, a, b, c, out var feature);
                            float dist2 = Vector3.DistanceSquared(p, q);
                            int i = x + Nx * (y + Ny * z);
                            if (dist2 > band2) continue;
                            float dist = MathF.Sqrt(dist2);
                            if (dist >= d[i]) continue;
                            d[i] = dist;
                            sign[i] = (sbyte)(Vector3.Dot(p - q, pseudo.Normal(t, feature)) < 0f ? -1 : 1);
                        }
            }
        });

        // Beyond the band: outside if reachable from the grid's border without crossing the band, else inside.
        var outside = new bool[d.Length];
        var queue = new Queue<int>();
        void Seed(int i) { if (!outside[i] && d[i] == float.MaxValue) { outside[i] = true; queue.Enqueue(i); } }
        for (int z = 0; z < Nz; z++)
            for (int y = 0; y < Ny; y++)
                for (int x = 0; x < Nx; x++)
                    if (x == 0 || y == 0 || z == 0 || x == Nx - 1 || y == Ny - 1 || z == Nz - 1) Seed(x + Nx * (y + Ny * z));
        while (queue.Count > 0)
        {
            int i = queue.Dequeue();
            int x = i % Nx, y = i / Nx % Ny, z = i / (Nx * Ny);
            if (x > 0) Seed(i - 1);
            if (x < Nx - 1) Seed(i + 1);
            if (y > 0) Seed(i - Nx);
            if (y < Ny - 1) Seed(i + Nx);
            if (z > 0) Seed(i - Nx * Ny);
            if (z < Nz - 1) Seed(i + Nx * Ny);
        }
        // Beyond the band, a chamfer distance (26 neighbours, two sweeps) from the band's exact values: hair that got
        // deeper than the band in one substep still has a gradient that leads it out.
        float[] w = [cellSize, cellSize * MathF.Sqrt(2f), cellSize * MathF.Sqrt(3f)];
        for (int pass = 0; pass < 2; pass++)
        {
            int step = pass == 0 ? 1 : -1;
            for (int z = pass == 0 ? 0 : Nz - 1; z >= 0 && z < Nz; z += step)
                for (int y = pass == 0 ? 0 : Ny - 1; y >= 0 && y < Ny; y += step)
                    for (int x = pass == 0 ? 0 : Nx - 1; x >= 0 && x < Nx; x += step)
                    {
                        int i = x + Nx * (y + Ny * z);
                        float best = d[i];
                        for (int dz = -1; dz <= 0; dz++)
                            for (int dy = -1; dy <= 1; dy++)
                                for (int dx = -1; dx <= 1; dx++)
                                {
                                    // Half of the neighbourhood: the cells this sweep has already visited.
                                    if (dz == 0 && (dy > 0 || (dy == 0 && dx >= 0))) continue;
                                    int nxp = x + step * dx, nyp = y + step * dy, nzp = z + step * dz;
                                    if (nxp < 0 || nyp < 0 || nzp < 0 || nxp >= Nx || nyp >= Ny || nzp >= Nz) continue;
                                    float v = d[nxp + Nx * (nyp + Ny * nzp)];
                                    if (v == float.MaxValue) continue;
                                    best = MathF.Min(best, v + w[Math.Abs(dx) + Math.Abs(dy) + Math.Abs(dz) - 1]);
                                }
                        d[i] = best;
                    }
        }
        for (int i = 0; i < d.Length; i++)
            d[i] = sign[i] != 0 ? sign[i] * d[i] : outside[i] ? d[i] : -d[i];
        return d;
    }

    /// <summary>The mesh's connected parts (triangles sharing welded vertices), each a closed shell of its own.</summary>
    private static List<TriangleMesh> Parts(TriangleMesh mesh, int[] weld)
    {
        var p = mesh.Positions;
        var parent = new int[p.Length];
        for (int i = 0; i < parent.Length; i++) parent[i] = weld[i];
        int Find(int i) { while (parent[i] != i) i = parent[i] = parent[parent[i]]; return i; }
        var idx = mesh.Indices;
        for (int t = 0; t < idx.Length; t += 3) { parent[Find(idx[t + 1])] = Find(idx[t]); parent[Find(idx[t + 2])] = Find(idx[t]); }
        var groups = new Dictionary<int, List<int>>();
        for (int t = 0; t < idx.Length; t += 3)
        {
            int r = Find(idx[t]);
            if (!groups.TryGetValue(r, out var g)) groups[r] = g = new List<int>();
            g.Add(t / 3);
        }
        if (groups.Count == 1) return [mesh];
        var parts = new List<TriangleMesh>(groups.Count);
        foreach (var tris in groups.Values)
        {
            var sub = new int[3 * tris.Count];
            for (int k = 0; k < tris.Count; k++) { sub[3 * k] = idx[3 * tris[k]]; sub[3 * k + 1] = idx[3 * tris[k] + 1]; sub[3 * k + 2] = idx[3 * tris[k] + 2]; }
            parts.Add(new TriangleMesh(p, sub, mesh.Colors));
        }
        return parts;
    }


    /// <summary>The baked distances, x fastest then y then z (a copy: for storing the field, e.g. in a Godot resource).</summary>
    public float[] CopyDistances() => (float[])_d.Clone();

    /// <summary>A field stored earlier (<see cref="CopyDistances"/> and the grid's shape); checked, so a corrupt store is refused.</summary>
    public static SignedDistanceField FromData(Vector3 origin, float cellSize, int nx, int ny, int nz, float[] distances)
    {
        ArgumentNullException.ThrowIfNull(distances);
        if (!float.IsFinite(origin.X + origin.Y + origin.Z)) throw new ArgumentException("The field's origin is not finite.", nameof(origin));
        if (!float.IsFinite(cellSize) || cellSize <= 0f) throw new ArgumentOutOfRangeException(nameof(cellSize), cellSize, "Cell size must be positive.");
        if (nx < 2 || ny < 2 || nz < 2 || (long)nx * ny * nz > MaxCells)
            throw new ArgumentOutOfRangeException(nameof(nx), $"A field has 2 … {MaxCells:N0} cells with at least two each way; got {nx}×{ny}×{nz}.");
        if (distances.Length != nx * ny * nz) throw new ArgumentException($"{distances.Length} distances for {nx}×{ny}×{nz} cells.", nameof(distances));
        foreach (float v in distances) if (!float.IsFinite(v)) throw new ArgumentException("The field holds a non-finite distance.", nameof(distances));
        return new SignedDistanceField(origin, cellSize, nx, ny, nz, (float[])distances.Clone(), TimeSpan.Zero);
    }

    /// <summary>
    /// Signed distance at p (metres; negative inside), trilinear between cells. Outside the grid (which holds the whole
    /// surface at least the band inside its boundary) the field at the grid's nearest point plus the distance to it:
    /// continuous across the boundary, and changing by at most √3 × a move anywhere, as the trilinear field does inside
    /// (the collision kernel's records rely on that), so hair hanging below a head is known to be far from it.
    /// </summary>
    public float Distance(Vector3 p) => DistanceAt(p.X, p.Y, p.Z);

    /// <summary>
    /// The value outside the grid, from grid coordinates (see <see cref="Distance(Vector3)"/>): the trilinear field at
    /// the nearest grid point (a point on the top face is its last cell at fraction 1) plus the distance to it. Its
    /// slope across a face is 1 and along it at most √2, so at most √3 in all. A NaN coordinate gives NaN.
    /// </summary>
    private float Outside(float gx, float gy, float gz)
    {
        // Written as the kernel's maxps/minps: a NaN coordinate clamps to 0 and the distance to the grid stays NaN.
        float cx = gx > 0f ? gx : 0f, cy = gy > 0f ? gy : 0f, cz = gz > 0f ? gz : 0f;
        cx = cx < _hx ? cx : _hx; cy = cy < _hy ? cy : _hy; cz = cz < _hz ? cz : _hz;
        float ex = gx - cx, ey = gy - cy, ez = gz - cz;
        float beyond = MathF.Sqrt(ex * ex + ey * ey + ez * ez) * CellSize;
        int x = Math.Min((int)cx, Nx - 2), y = Math.Min((int)cy, Ny - 2), z = Math.Min((int)cz, Nz - 2);
        return Trilinear(x, y, z, cx - x, cy - y, cz - z) + beyond;
    }

    /// <summary>The trilinear field in cell (x, y, z) at fractions (fx, fy, fz), in the kernel's order of operations.</summary>
    private float Trilinear(int x, int y, int z, float fx, float fy, float fz)
    {
        int i = x + Nx * y + Nx * Ny * z, sy = Nx, sz = Nx * Ny;
        var d = _d;
        float x00 = d[i] + fx * (d[i + 1] - d[i]), x10 = d[i + sy] + fx * (d[i + sy + 1] - d[i + sy]);
        float x01 = d[i + sz] + fx * (d[i + sz + 1] - d[i + sz]), x11 = d[i + sz + sy] + fx * (d[i + sz + sy + 1] - d[i + sz + sy]);
        float y0 = x00 + fy * (x10 - x00), y1 = x01 + fy * (x11 - x01);
        return y0 + fz * (y1 - y0);
    }

    /// <summary>
    /// <see cref="Distance(Vector3)"/> with every operation written out, in the order the vectorised collision kernel
    /// (FastMeshCollideSystem) does them, so both give the same bits.
    /// </summary>
    internal float DistanceAt(float px, float py, float pz)
    {
        float gx = (px - Origin.X) * InvCell, gy = (py - Origin.Y) * InvCell, gz = (pz - Origin.Z) * InvCell;
        if (!(gx >= 0f && gy >= 0f && gz >= 0f && gx < _hx && gy < _hy && gz < _hz)) return Outside(gx, gy, gz);
        int x = (int)gx, y = (int)gy, z = (int)gz;
        return Trilinear(x, y, z, gx - x, gy - y, gz - z);
    }

    /// <summary>Signed distance and its gradient (not normalised) at p; outside the grid, <see cref="Distance(Vector3)"/>'s value and a zero gradient.</summary>
    public float Sample(Vector3 p, out Vector3 gradient)
    {
        float d = SampleAt(p.X, p.Y, p.Z, out float gx, out float gy, out float gz);
        gradient = new Vector3(gx, gy, gz);
        return d;
    }

    /// <summary><see cref="Sample(Vector3, out Vector3)"/> written out as the vectorised kernel does it (see <see cref="DistanceAt"/>).</summary>
    internal float SampleAt(float px, float py, float pz, out float gradX, out float gradY, out float gradZ)
    {
        float gx = (px - Origin.X) * InvCell, gy = (py - Origin.Y) * InvCell, gz = (pz - Origin.Z) * InvCell;
        if (!(gx >= 0f && gy >= 0f && gz >= 0f && gx < _hx && gy < _hy && gz < _hz))
        {
            gradX = gradY = gradZ = 0f;
            return Outside(gx, gy, gz);   // outside the grid: never pushed
        }
        int x = (int)gx, y = (int)gy, z = (int)gz;
        float fx = gx - x, fy = gy - y, fz = gz - z;
        int i = x + Nx * y + Nx * Ny * z, sy = Nx, sz = Nx * Ny;
        var d = _d;
        float d000 = d[i], d100 = d[i + 1], d010 = d[i + sy], d110 = d[i + sy + 1];
        float d001 = d[i + sz], d101 = d[i + sz + 1], d011 = d[i + sz + sy], d111 = d[i + sz + sy + 1];
        float x00 = d000 + fx * (d100 - d000), x10 = d010 + fx * (d110 - d010), x01 = d001 + fx * (d101 - d001), x11 = d011 + fx * (d111 - d011);
        float y0 = x00 + fy * (x10 - x00), y1 = x01 + fy * (x11 - x01);
        float ux = 1f - fy, uz = 1f - fz;
        gradX = (uz * (ux * (d100 - d000) + fy * (d110 - d010)) + fz * (ux * (d101 - d001) + fy * (d111 - d011))) * InvCell;
        gradY = (uz * (x10 - x00) + fz * (x11 - x01)) * InvCell;
        gradZ = (y1 - y0) * InvCell;
        return y0 + fz * (y1 - y0);
    }

    /// <summary>Closest point on triangle abc to p (Ericson, Real-Time Collision Detection §5.1.5) and which feature it is on.</summary>
    internal static Vector3 ClosestOnTriangle(Vector3 p, Vector3 a, Vector3 b, Vector3 c, out Feature feature)
    {
        var ab = b - a; var ac = c - a; var ap = p - a;
        float d1 = Vector3.Dot(ab, ap), d2 = Vector3.Dot(ac, ap);
        if (d1 <= 0f && d2 <= 0f) { feature = Feature.VertexA; return a; }
        var bp = p - b;
        float d3 = Vector3.Dot(ab, bp), d4 = Vector3.Dot(ac, bp);
        if (d3 >= 0f && d4 <= d3) { feature = Feature.VertexB; return b; }
        float vc = d1 * d4 - d3 * d2;
        if (vc <= 0f && d1 >= 0f && d3 <= 0f) { feature = Feature.EdgeAB; return a + d1 / (d1 - d3) * ab; }
        var cp = p - c;
        float d5 = Vector3.Dot(ab, cp), d6 = Vector3.Dot(ac, cp);
        if (d6 >= 0f && d5 <= d6) { feature = Feature.VertexC; return c; }
        float vb = d5 * d2 - d1 * d6;
        if (vb <= 0f && d2 >= 0f && d6 <= 0f) { feature = Feature.EdgeCA; return a + d2 / (d2 - d6) * ac; }
        float va = d3 * d6 - d5 * d4;
        if (va <= 0f && d4 - d3 >= 0f && d5 - d6 >= 0f) { feature = Feature.EdgeBC; return b + (d4 - d3) / (d4 - d3 + (d5 - d6)) * (c - b); }
        float denom = 1f / (va + vb + vc);
        feature = Feature.Face;
        return a + ab * (vb * denom) + ac * (vc * denom);
    }

    /// <summary>For each vertex, the first vertex at the same position (glTF exports split vertices along UV seams).</summary>
    private static int[] Weld(Vector3[] p)
    {
        var weld = new int[p.Length];
        var seen = new Dictionary<Vector3, int>();
        for (int i = 0; i < p.Length; i++) weld[i] = seen.TryGetValue(p[i], out int j) ? j : (seen[p[i]] = i);
        return weld;
    }

    internal enum Feature { Face, VertexA, VertexB, VertexC, EdgeAB, EdgeBC, EdgeCA }

    /// <summary>
    /// Angle-weighted vertex normals and edge normals (sum of the two faces') over welded vertices, so a mesh whose
    /// vertices are split along UV seams (as glTF exports are) still has one normal per corner.
    /// </summary>
    private sealed class PseudoNormals
    {
        private readonly TriangleMesh _mesh;
        private readonly int[] _weld;
        private readonly Vector3[] _vertex;
        // Keyed by the (low, high) vertex pair: a long key would hash as low ^ high, which collides for most edges of a mesh.
        private readonly Dictionary<(int, int), Vector3> _edge = new();

        public PseudoNormals(TriangleMesh mesh, int[] weld)
        {
            _mesh = mesh;
            var p = mesh.Positions;
            _weld = weld;
            _vertex = new Vector3[p.Length];
            for (int t = 0; t < mesh.TriangleCount; t++)
            {
                var n = mesh.FaceNormal(t);
                for (int k = 0; k < 3; k++)
                {
                    int v = mesh.Indices[3 * t + k], v1 = mesh.Indices[3 * t + (k + 1) % 3], v2 = mesh.Indices[3 * t + (k + 2) % 3];
                    var e1 = p[v1] - p[v]; var e2 = p[v2] - p[v];
                    float l = e1.Length() * e2.Length();
                    float angle = l > 0f ? MathF.Acos(Math.Clamp(Vector3.Dot(e1, e2) / l, -1f, 1f)) : 0f;
                    _vertex[_weld[v]] += angle * n;
                    var key = EdgeKey(_weld[v], _weld[v1]);
                    _edge[key] = _edge.TryGetValue(key, out var s) ? s + n : n;
                }
            }
        }

        private static (int, int) EdgeKey(int a, int b) => a < b ? (a, b) : (b, a);

        public Vector3 Normal(int t, Feature f)
        {
            var idx = _mesh.Indices;
            int a = _weld[idx[3 * t]], b = _weld[idx[3 * t + 1]], c = _weld[idx[3 * t + 2]];
            return f switch
            {
                Feature.VertexA => _vertex[a],
                Feature.VertexB => _vertex[b],
                Feature.VertexC => _vertex[c],
                Feature.EdgeAB => _edge[EdgeKey(a, b)],
                Feature.EdgeBC => _edge[EdgeKey(b, c)],
                Feature.EdgeCA => _edge[EdgeKey(c, a)],
                _ => _mesh.FaceNormal(t),
            };
        }
    }
}
