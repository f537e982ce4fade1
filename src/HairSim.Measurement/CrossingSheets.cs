using System.Numerics;

namespace HairSim.Measurement;

/// <summary>
/// What <see cref="CrossingSheets.Run"/> found: crossings measured, how many of them the upper sheet ended at or below
/// the lower, how many it ended in the lower sheet's layer (at or below it, or less than
/// <see cref="CrossingSheets.LayerShare"/> of the length above it), the mean gap (as a share of the strand length),
/// non-finite values, the parts (volume passes) per frame the pipeline stepped on average, and the worst segment
/// length error at the end (|length / rest length − 1| over every segment of both sheets).
/// </summary>
public readonly record struct CrossingResult(int Crossings, int Sunk, double MeanGap, int NonFinite, double PartsPerFrame = 1, int InLayer = 0, double LengthError = 0)
{
    public double SunkShare => Crossings > 0 ? (double)Sunk / Crossings : double.NaN;
}

/// <summary>
/// Two crossing sheets of limp hair: sheet A (20 strands of 16 particles along x, 4 % of the length apart) lies on a
/// nearly flat floor; sheet B, the same strands along z, starts above A and falls onto it under 1 g. Both are pinned at
/// their roots and rest on the floor with friction. After 3 natural seconds the heights of A and B are compared wherever
/// a strand of B crosses a strand of A seen from above (about 400 crossings as dropped): without hair–hair interaction B
/// falls into A's layer and ends below it at about half the crossings; a volume that keeps layers apart leaves B above
/// A at nearly every one, and strand contacts (<see cref="StrandContactSettings"/>) at every one.
/// Everything scales with <c>scale</c> (1 = 25 cm strands), times with √scale (Froude), so the case is the same at any size.
/// </summary>
public static class CrossingSheets
{
    public const int Strands = 20, Particles = 16;

    /// <summary>
    /// B less than this share of the strand length above A at a crossing counts as in A's layer: strands have no
    /// thickness here, so "at or below" alone flips on float-level differences where B lies in A's plane (on the floor
    /// beside A's strands); a B strand resting on A sits several per cent of the length above it (a volume cell).
    /// </summary>
    public const double LayerShare = 0.01;

    public static HairScene Scene(VolumeSettings? volume, SolverPath path, float drop = 0.12f, float scale = 1f, StrandContactSettings? contacts = null)
    {
        float length = 0.25f * scale, spacing = 0.04f * length;
        var w = new HairWorld(2, Strands, Particles);
        var points = new Vector3[Particles];
        for (int i = 0; i < Strands; i++)
        {
            float z = (i - (Strands - 1) / 2f) * spacing;
            for (int k = 0; k < Particles; k++) points[k] = new Vector3(length * k / (Particles - 1), 0.0005f * length, z);
            w.SetStrand(i, points, pinned: 1);
            float x = 0.1f * length + i * spacing;
            for (int k = 0; k < Particles; k++) points[k] = new Vector3(x, drop * length, -0.48f * length + length * k / (Particles - 1));
            w.SetStrand(Strands + i, points, pinned: 1);
        }
        var settings = new SimulationSettings { Bend = BendModel.Limp, Path = path, StaticFriction = 1f, KineticFriction = 1f };
        var scene = new HairScene(w, settings);
        // A floor: the top of a wide, flat ellipsoid.
        scene.AddCollider(Collider.Ellipsoid(new Vector3(0.5f * length, -2f * length, 0f), new Vector3(20f * length, 2f * length, 20f * length)));
        if (volume != null) scene.SetComponent(volume);
        if (contacts != null) scene.SetComponent(contacts);
        return scene;
    }

    /// <summary>Drops sheet B from <paramref name="drop"/> strand lengths above A and runs 3 s × √scale at <paramref name="hz"/>.</summary>
    public static CrossingResult Run(VolumeSettings? volume, SolverPath path, int hz, float drop = 0.12f, float scale = 1f, IThreadDispatcher? dispatcher = null,
        StrandContactSettings? contacts = null)
    {
        var scene = Scene(volume, path, drop, scale, contacts);
        var sim = new HairSimulation(scene, dispatcher: dispatcher);
        int frames = (int)Math.Ceiling(3.0 * Math.Sqrt(scale) * hz);
        long parts = 0;
        for (int f = 0; f < frames; f++) { sim.Step(1f / hz); parts += sim.Pipeline.LastFrameParts; }
        return Measure(scene.World, 0.25f * scale) with { PartsPerFrame = (double)parts / frames };
    }

    /// <summary>
    /// Heights of A and B wherever a segment of a strand of B crosses a segment of a strand of A seen from above (in the
    /// floor's plane), so strands that bend sideways are still measured where they cross.
    /// </summary>
    public static CrossingResult Measure(HairWorld w, float length)
    {
        int crossings = 0, sunk = 0, inLayer = 0; double gaps = 0;
        for (int i = 0; i < Strands; i++)
        {
            var a = w.GetStrandPositions(i);
            for (int j = 0; j < Strands; j++)
            {
                var b = w.GetStrandPositions(Strands + j);
                for (int p = 1; p < a.Length; p++)
                    for (int q = 1; q < b.Length; q++)
                    {
                        if (!Cross(a[p - 1], a[p], b[q - 1], b[q], out float s, out float t)) continue;
                        double ya = a[p - 1].Y + s * (a[p].Y - a[p - 1].Y), yb = b[q - 1].Y + t * (b[q].Y - b[q - 1].Y);
                        crossings++; gaps += yb - ya;
                        if (yb <= ya) sunk++;
                        if (yb - ya < LayerShare * length) inLayer++;
                    }
            }
        }
        double worst = 0;
        for (int s = 0; s < w.StrandCount; s++)
            for (int i = w.StrandFirst[s] + 1, e = w.StrandFirst[s] + w.StrandParticleCount[s]; i < e; i++)
                worst = Math.Max(worst, Math.Abs(Vector3.Distance(w.GetPosition(i), w.GetPosition(i - 1)) / w.RestLength[i] - 1));
        return new CrossingResult(crossings, sunk, crossings > 0 ? gaps / crossings / length : double.NaN, w.CountNonFinite(), InLayer: inLayer, LengthError: worst);
    }

    /// <summary>
    /// The sheets seen along A's strands (x): A's strands end-on, as short dark marks along z, and B's strands as blue
    /// lines across them; heights exaggerated <paramref name="stretch"/> times so a layer a hundredth of the length thick
    /// shows. An SVG picture, <paramref name="title"/> on top.
    /// </summary>
    public static string SideView(HairWorld w, float length, string title, float stretch = 8f)
    {
        const float width = 640f, height = 220f, left = 20f, right = 20f, top = 28f, bottom = 20f;
        float z0 = -0.55f * length, z1 = 0.55f * length, y0 = -0.01f * length, y1 = 0.01f * length + (height - top - bottom) / (width - left - right) * (z1 - z0) / stretch;
        var ic = System.Globalization.CultureInfo.InvariantCulture;
        string X(float z) => (left + (z - z0) / (z1 - z0) * (width - left - right)).ToString("F1", ic);
        string Y(float y) => (height - bottom - (Math.Clamp(y, y0, y1) - y0) / (y1 - y0) * (height - top - bottom)).ToString("F1", ic);
        var sb = new System.Text.StringBuilder();
        sb.Append($"<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" viewBox=\"0 0 {width} {height}\">\n");
        sb.Append($"<rect width=\"{width}\" height=\"{height}\" fill=\"white\"/>\n");
        sb.Append($"<text x=\"{left}\" y=\"18\" font-family=\"sans-serif\" font-size=\"13\">{System.Security.SecurityElement.Escape(title)}</text>\n");
        sb.Append($"<line x1=\"{left}\" y1=\"{Y(0f)}\" x2=\"{width - right}\" y2=\"{Y(0f)}\" stroke=\"#bbb\" stroke-dasharray=\"4 3\"/>\n");
        for (int s = Strands; s < 2 * Strands; s++) Polyline(sb, w, s, "#2563eb", 1.2f, X, Y);
        for (int s = 0; s < Strands; s++) Polyline(sb, w, s, "#111", 2.5f, X, Y);
        sb.Append("</svg>\n");
        return sb.ToString();
    }

    private static void Polyline(System.Text.StringBuilder sb, HairWorld w, int s, string colour, float stroke, Func<float, string> x, Func<float, string> y)
    {
        sb.Append("<polyline fill=\"none\" stroke=\"").Append(colour).Append("\" stroke-width=\"").Append(stroke.ToString(System.Globalization.CultureInfo.InvariantCulture)).Append("\" points=\"");
        foreach (var p in w.GetStrandPositions(s)) sb.Append(x(p.Z)).Append(',').Append(y(p.Y)).Append(' ');
        sb.Append("\"/>\n");
    }

    // Whether segments p0p1 and q0q1 cross in the xz plane, and where along each (0 … 1).
    private static bool Cross(Vector3 p0, Vector3 p1, Vector3 q0, Vector3 q1, out float s, out float t)
    {
        s = t = 0f;
        float rx = p1.X - p0.X, rz = p1.Z - p0.Z, ux = q1.X - q0.X, uz = q1.Z - q0.Z;
        float den = rx * uz - rz * ux;
        if (MathF.Abs(den) < 1e-12f) return false;
        float dx = q0.X - p0.X, dz = q0.Z - p0.Z;
        s = (dx * uz - dz * ux) / den;
        t = (dx * rz - dz * rx) / den;
        return s >= 0f && s < 1f && t >= 0f && t < 1f;
    }
}
