using System.Numerics;

namespace HairSim.Meshes;

/// <summary>Where hair grows on a mesh and how it is combed.</summary>
public sealed class MeshGroomSettings
{
    /// <summary>Hair sheets to make (roots are grouped into this many patches; each becomes a skeleton + sub-skeletons).</summary>
    public int SheetCount { get; set; } = 435;
    /// <summary>Roots in all = SheetCount × StrandsPerSheet.</summary>
    public int StrandsPerSheet { get; set; } = 40;
    public int ParticlesPerStrand { get; set; } = 16;
    public float StrandLength { get; set; } = 0.25f;
    public int PinnedPerStrand { get; set; } = 2;
    /// <summary>Hair starts this far above the surface (metres).</summary>
    public float RootLift { get; set; } = 0.002f;
    /// <summary>0: strands stand out along the surface normal; 1: they turn to hang down within about a quarter of the head's size.</summary>
    public float Drape { get; set; } = 1f;
    /// <summary>Where hair grows: a vertex whose colour's red channel is at least this is scalp (0 = everywhere; meshes without colours grow everywhere).</summary>
    public float ScalpMaskThreshold { get; set; }
    /// <summary>A painted scalp (<see cref="ScalpPaint"/>, made for this mesh): when set, its triangles are the scalp and the colour mask is not used.</summary>
    public ScalpPaint? Scalp { get; set; }
    /// <summary>Further limit on the scalp (head space); null = none. For example "above the ears": p => p.Y > 0.</summary>
    public Func<Vector3, Vector3, bool>? ScalpFilter { get; set; }
    public ulong Seed { get; set; } = 2009;

    public void Validate()
    {
        if (SheetCount < 1 || StrandsPerSheet < 1 || (long)SheetCount * StrandsPerSheet > 1_000_000)
            throw new ArgumentOutOfRangeException(nameof(SheetCount), "Sheets and strands per sheet must be at least 1, and at most a million strands in all.");
        if (ParticlesPerStrand < 2 || ParticlesPerStrand > HairWorld.MaxParticlesPerStrand)
            throw new ArgumentOutOfRangeException(nameof(ParticlesPerStrand), ParticlesPerStrand, "Particles per strand must be 2 … 4096.");
        if (PinnedPerStrand < 1 || PinnedPerStrand >= ParticlesPerStrand)
            throw new ArgumentOutOfRangeException(nameof(PinnedPerStrand), PinnedPerStrand, "Pinned particles must be at least 1 and fewer than the particles per strand.");
        if (!float.IsFinite(StrandLength) || StrandLength <= 0f || StrandLength > 1000f)
            throw new ArgumentOutOfRangeException(nameof(StrandLength), StrandLength, "Strand length must be in (0, 1000] metres.");
        if (!float.IsFinite(RootLift) || RootLift < 0f) throw new ArgumentOutOfRangeException(nameof(RootLift), RootLift, "Root lift must be 0 or more.");
        if (!float.IsFinite(Drape) || Drape < 0f || Drape > 1f) throw new ArgumentOutOfRangeException(nameof(Drape), Drape, "Drape must be 0 … 1.");
    }
}

/// <summary>
/// Grows hair sheets on a mesh: roots spread evenly over the scalp triangles (area-weighted candidates thinned to a
/// minimum spacing, so no streaks and no clumps), grouped into sheets by nearness (k-means), each sheet's strands
/// ordered across it so the middle one is its skeleton strand; strands leave along the surface normal and turn
/// down, kept outside the mesh by its distance field.
/// </summary>
public static class MeshScalp
{
    public static HairScene BuildScene(TriangleMesh mesh, SignedDistanceField field, MeshGroomSettings g, SimulationSettings? settings = null)
    {
        var scene = new HairScene(Grow(mesh, field, g), settings);
        scene.SetComponent(new MeshCollider(field, Math.Min(g.RootLift * 0.5f, field.Band * 0.5f), mesh));
        return scene;
    }

    public static HairWorld Grow(TriangleMesh mesh, SignedDistanceField field, MeshGroomSettings g)
    {
        ArgumentNullException.ThrowIfNull(mesh);
        ArgumentNullException.ThrowIfNull(field);
        ArgumentNullException.ThrowIfNull(g);
        g.Validate();
        if (g.Scalp != null && !ReferenceEquals(g.Scalp.Mesh, mesh) && g.Scalp.Mesh.TriangleCount != mesh.TriangleCount)
            throw new ArgumentException($"The painted scalp was made for a mesh of {g.Scalp.Mesh.TriangleCount} triangles; this one has {mesh.TriangleCount}.", nameof(g));
        var rng = new Random(unchecked((int)g.Seed));
        int want = g.SheetCount * g.StrandsPerSheet;

        // Scalp triangles and their areas.
        var tris = new List<int>();
        var cumulative = new List<double>();
        double total = 0;
        for (int t = 0; t < mesh.TriangleCount; t++)
        {
            if (!OnScalp(mesh, g, t)) continue;
            float a = mesh.TriangleArea(t);
            if (!(a > 0f)) continue;
            total += a; tris.Add(t); cumulative.Add(total);
        }
        if (tris.Count == 0) throw new ArgumentException("No triangle is on the scalp: check the mask threshold and filter.");

        // Candidates area-weighted, then thinned to a spacing that leaves about `want` roots (a few rounds of halving).
        int candidates = Math.Max(want * 4, 64);
        var points = new (Vector3 P, Vector3 N)[candidates];
        for (int k = 0; k < candidates; k++)
        {
            int i = cumulative.BinarySearch(rng.NextDouble() * total);
            int t = tris[i < 0 ? Math.Min(~i, tris.Count - 1) : i];
            var (a, b, c) = mesh.Triangle(t);
            float u = (float)rng.NextDouble(), v = (float)rng.NextDouble();
            if (u + v > 1f) { u = 1f - u; v = 1f - v; }
            points[k] = (a + u * (b - a) + v * (c - a), mesh.FaceNormal(t));
        }
        // A scalp triangle inside another part of the mesh (an ear modelled into the head) grows nothing, nor does one
        // so close to another part that its lifted root would be in it (roots are pinned: collision cannot move them).
        points = points.Where(c => field.Distance(c.P) > -0.5f * field.CellSize && field.Distance(c.P + c.N * g.RootLift) > 0.5f * g.RootLift).ToArray();
        float spacing = (float)Math.Sqrt(total / want) * 0.9f;
        List<(Vector3 P, Vector3 N)> roots;
        do { roots = Thin(points, spacing); spacing *= 0.9f; } while (roots.Count < want && spacing > 1e-6f);
        if (roots.Count > want) roots.RemoveRange(want, roots.Count - want);
        if (roots.Count < want) throw new ArgumentException($"Only {roots.Count} roots fit on the scalp; ask for fewer strands.");

        // Sheets: k-means on root positions, then each sheet's strands sorted along its widest direction.
        var sheetOf = KMeans(roots, g.SheetCount, rng);
        var sheets = new List<int>[g.SheetCount];
        for (int s = 0; s < sheets.Length; s++) sheets[s] = new List<int>();
        for (int r = 0; r < roots.Count; r++) sheets[sheetOf[r]].Add(r);
        var nonEmpty = SideBySide(sheets.Where(s => s.Count > 0).ToList(), roots);
        var perSheet = nonEmpty.Select(s => s.Count).ToArray();
        var particles = Enumerable.Repeat(g.ParticlesPerStrand, roots.Count).ToArray();
        var world = new HairWorld(perSheet, particles);
        var pts = new Vector3[g.ParticlesPerStrand];
        float segment = g.StrandLength / (g.ParticlesPerStrand - 1);
        // Turning down with a bend radius of about a quarter of the scalp's size, as the ellipsoid groom does.
        var lo = new Vector3(float.MaxValue); var hi = new Vector3(float.MinValue);
        foreach (var r in roots) { lo = Vector3.Min(lo, r.P); hi = Vector3.Max(hi, r.P); }
        var half = (hi - lo) * 0.5f;
        float turn = g.Drape * segment * 12f / MathF.Max(1e-6f, half.X + half.Y + half.Z);
        int strand = 0;
        foreach (var members in nonEmpty)
        {
            var centre = Vector3.Zero;
            foreach (int r in members) centre += roots[r].P;
            centre /= members.Count;
            var axis = WidestDirection(members.Select(r => roots[r].P - centre));
            members.Sort((x, y) => Vector3.Dot(roots[x].P - centre, axis).CompareTo(Vector3.Dot(roots[y].P - centre, axis)));
            foreach (int r in members)
            {
                Comb(field, roots[r].P, roots[r].N, g, segment, turn, pts);
                world.SetStrand(strand++, pts, g.PinnedPerStrand);
            }
        }
        world.ResetToRest();
        return world;
    }

    private static bool OnScalp(TriangleMesh mesh, MeshGroomSettings g, int t)
    {
        if (g.Scalp != null) { if (!g.Scalp.IsScalp(t)) return false; }
        else if (g.ScalpMaskThreshold > 0f && mesh.Colors != null)
        {
            var c = mesh.Colors;
            var idx = mesh.Indices;
            float red = (c[idx[3 * t]].X + c[idx[3 * t + 1]].X + c[idx[3 * t + 2]].X) / 3f;
            if (red < g.ScalpMaskThreshold) return false;
        }
        if (g.ScalpFilter != null)
        {
            var (a, b, cc) = mesh.Triangle(t);
            if (!g.ScalpFilter((a + b + cc) / 3f, mesh.FaceNormal(t))) return false;
        }
        return true;
    }

    /// <summary>Keeps candidates (in their random order) that are at least `spacing` from every kept one (a hash grid).</summary>
    private static List<(Vector3 P, Vector3 N)> Thin((Vector3 P, Vector3 N)[] candidates, float spacing)
    {
        var kept = new List<(Vector3 P, Vector3 N)>();
        var grid = new Dictionary<(int, int, int), List<int>>();
        float s2 = spacing * spacing;
        (int, int, int) Cell(Vector3 p) => ((int)MathF.Floor(p.X / spacing), (int)MathF.Floor(p.Y / spacing), (int)MathF.Floor(p.Z / spacing));
        foreach (var c in candidates)
        {
            var (cx, cy, cz) = Cell(c.P);
            bool near = false;
            for (int dz = -1; dz <= 1 && !near; dz++)
                for (int dy = -1; dy <= 1 && !near; dy++)
                    for (int dx = -1; dx <= 1 && !near; dx++)
                        if (grid.TryGetValue((cx + dx, cy + dy, cz + dz), out var list))
                            foreach (int k in list) if (Vector3.DistanceSquared(kept[k].P, c.P) < s2) { near = true; break; }
            if (near) continue;
            if (!grid.TryGetValue((cx, cy, cz), out var own)) grid[(cx, cy, cz)] = own = new List<int>();
            own.Add(kept.Count);
            kept.Add(c);
        }
        return kept;
    }

    /// <summary>
    /// The sheets in an order that walks across the scalp (each next sheet the nearest one not yet taken, from the
    /// lowest): k-means numbers its clusters in no spatial order, and the solver steps strands in memory order, so
    /// sheets side by side in memory keep the collision's distance-field cells in cache from one strand chunk to the next.
    /// </summary>
    private static List<List<int>> SideBySide(List<List<int>> sheets, List<(Vector3 P, Vector3 N)> roots)
    {
        var centres = sheets.Select(s => s.Aggregate(Vector3.Zero, (a, r) => a + roots[r].P) / s.Count).ToArray();
        var taken = new bool[sheets.Count];
        var order = new List<List<int>>(sheets.Count);
        int at = 0;
        for (int s = 1; s < centres.Length; s++) if (centres[s].Y < centres[at].Y) at = s;
        while (true)
        {
            taken[at] = true;
            order.Add(sheets[at]);
            int next = -1; float best = float.MaxValue;
            for (int s = 0; s < centres.Length; s++)
                if (!taken[s] && Vector3.DistanceSquared(centres[s], centres[at]) is var d && d < best) { best = d; next = s; }
            if (next < 0) return order;
            at = next;
        }
    }

    private static int[] KMeans(List<(Vector3 P, Vector3 N)> roots, int k, Random rng)
    {
        k = Math.Min(k, roots.Count);
        var centres = new Vector3[k];
        for (int c = 0; c < k; c++) centres[c] = roots[(int)((long)c * roots.Count / k)].P;
        var of = new int[roots.Count];
        var sum = new Vector3[k]; var count = new int[k];
        for (int it = 0; it < 8; it++)
        {
            Array.Clear(sum); Array.Clear(count);
            for (int r = 0; r < roots.Count; r++)
            {
                int best = 0; float bd = float.MaxValue;
                for (int c = 0; c < k; c++) { float d = Vector3.DistanceSquared(roots[r].P, centres[c]); if (d < bd) { bd = d; best = c; } }
                of[r] = best; sum[best] += roots[r].P; count[best]++;
            }
            for (int c = 0; c < k; c++) centres[c] = count[c] > 0 ? sum[c] / count[c] : roots[rng.Next(roots.Count)].P;
        }
        return of;
    }

    private static Vector3 WidestDirection(IEnumerable<Vector3> offsets)
    {
        // Power iteration on the covariance: the direction the patch is widest in.
        float xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
        foreach (var o in offsets) { xx += o.X * o.X; xy += o.X * o.Y; xz += o.X * o.Z; yy += o.Y * o.Y; yz += o.Y * o.Z; zz += o.Z * o.Z; }
        var v = new Vector3(1, 0.5f, 0.25f);
        for (int i = 0; i < 16; i++)
        {
            var n = new Vector3(xx * v.X + xy * v.Y + xz * v.Z, xy * v.X + yy * v.Y + yz * v.Z, xz * v.X + yz * v.Y + zz * v.Z);
            if (n.LengthSquared() < 1e-30f) return Vector3.UnitX;
            v = Vector3.Normalize(n);
        }
        return v;
    }

    /// <summary>Out of the surface along the normal for the pinned particles, then turning towards straight down, kept outside the mesh.</summary>
    private static void Comb(SignedDistanceField field, Vector3 root, Vector3 normal, MeshGroomSettings g, float segment, float turn, Vector3[] pts)
    {
        pts[0] = root + normal * g.RootLift;
        var dir = normal;
        var down = -Vector3.UnitY;
        for (int k = 1; k < pts.Length; k++)
        {
            if (k >= g.PinnedPerStrand && turn > 0f) dir = GroomBuilder.TurnTowards(dir, down, turn);
            var next = pts[k - 1] + dir * segment;
            for (int it = 0; it < 4; it++)
            {
                float d = field.Sample(next, out var grad);
                if (d >= g.RootLift || grad.LengthSquared() < 1e-12f) break;
                next += Vector3.Normalize(grad) * (g.RootLift - d);
                dir = Vector3.Normalize(next - pts[k - 1]);
                next = pts[k - 1] + dir * segment;
            }
            // Keeping the segment's length can leave the particle inside a thin part it was turned against (an ear):
            // then it goes out along the field's gradient instead (that segment grows a little longer than the others,
            // and keeps that rest length), rather than leaving a particle the collision must dig out of the ear.
            for (int it = 0; it < 8; it++)
            {
                float d = field.Sample(next, out var grad);
                if (d >= 0.5f * g.RootLift || grad.LengthSquared() < 1e-12f) break;
                next += Vector3.Normalize(grad) * (g.RootLift - d);
            }
            pts[k] = next;
        }
    }
}
