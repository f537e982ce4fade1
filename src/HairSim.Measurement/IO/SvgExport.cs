using System.Globalization;
using System.Numerics;

namespace HairSim.IO;

/// <summary>Simple pictures of a hairstyle: strands as polylines in an orthographic front or side view, with the head outline.</summary>
public static class SvgExport
{
    public enum View { Front, Side }

    /// <summary>
    /// Draws the live strands of the world (world space) looking along −Z (front) or −X (side), fitted to the
    /// given extent (metres around the head centre). Strands flagged in <paramref name="highlight"/> are drawn in a second colour;
    /// of the others only every <paramref name="every"/>-th is drawn (keeps pictures of the full scene small).
    /// </summary>
    public static void Write(TextWriter o, HairScene scene, View view, float extent = 0.6f, int pixels = 600, ReadOnlySpan<bool> highlight = default, string? title = null, int every = 1)
    {
        ArgumentNullException.ThrowIfNull(o);
        ArgumentNullException.ThrowIfNull(scene);
        if (every < 1) throw new ArgumentOutOfRangeException(nameof(every), every, "Draw at least every strand once (every ≥ 1).");
        if (!float.IsFinite(extent) || extent <= 0f) throw new ArgumentOutOfRangeException(nameof(extent), extent, "Extent must be positive.");
        if (pixels < 16 || pixels > 16384) throw new ArgumentOutOfRangeException(nameof(pixels), pixels, "Picture size must be 16 … 16384 pixels.");
        var w = scene.World;
        var ci = CultureInfo.InvariantCulture;
        var centre = w.Head.Position;
        float scale = pixels / extent;
        Vector2 Map(Vector3 p)
        {
            var d = p - centre;
            float x = view == View.Front ? d.X : -d.Z;
            return new Vector2(pixels * 0.5f + x * scale, pixels * 0.35f - d.Y * scale);
        }
        // Depth towards the viewer (front view: +Z, side view: +X), measured from the head's centre (the first drawn
        // collider's): hair behind that plane is drawn before the head, so the head covers it where they overlap, and
        // hair in front after it. Drawing all hair after the head put the hair at the back over the face.
        Vector3 depthCentre = centre;
        var meshCollider = scene.GetComponent<Meshes.MeshCollider>();
        var meshHead = meshCollider?.Mesh;
        var meshPose = meshCollider?.PoseFor(w.Head) ?? w.Head;
        if (meshHead != null) depthCentre = meshPose.TransformPoint(0.5f * (meshHead.BoundsMin + meshHead.BoundsMax));
        else
            foreach (var c in scene.Colliders)
                if (c.Kind is ColliderKind.Ellipsoid or ColliderKind.Sphere) { depthCentre = c.ToWorld(w.Head).Center; break; }
        bool Behind(Vector3 p) => (view == View.Front ? p.Z - depthCentre.Z : p.X - depthCentre.X) < 0f;

        o.Write($"<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{pixels}\" height=\"{pixels}\" viewBox=\"0 0 {pixels} {pixels}\">\n");
        o.Write("<rect width=\"100%\" height=\"100%\" fill=\"#fbfaf7\"/>\n");
        var sb = new System.Text.StringBuilder();
        bool[] highlightMask = highlight.ToArray(); // a span cannot be captured by the local function below
        void Hair(bool behind)
        {
            for (int pass = 0; pass < 2; pass++)
            {
                o.Write(pass == 0 ? "<g fill=\"none\" stroke=\"#5a3b24\" stroke-width=\"0.5\" stroke-opacity=\"0.5\">\n" : "<g fill=\"none\" stroke=\"#d2452b\" stroke-width=\"0.7\">\n");
                for (int s = 0; s < w.StrandCount; s++)
                {
                    bool lit = s < highlightMask.Length && highlightMask[s];
                    if (lit != (pass == 1) || (!lit && s % every != 0)) continue;
                    // The strand's runs on this side of the plane; a run keeps the segment that crosses the plane, so
                    // the two sides join without a gap.
                    int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
                    int k = 0;
                    while (k < n)
                    {
                        if (Behind(w.GetPosition(first + k)) != behind) { k++; continue; }
                        int from = Math.Max(0, k - 1), to = k;
                        while (to + 1 < n && Behind(w.GetPosition(first + to + 1)) == behind) to++;
                        if (to + 1 < n) to++;
                        sb.Clear();
                        sb.Append("<polyline points=\"");
                        for (int i = from; i <= to; i++)
                        {
                            var p = Map(w.GetPosition(first + i));
                            sb.Append(ci, $"{p.X:F1},{p.Y:F1} ");
                        }
                        sb.Append("\"/>\n");
                        o.Write(sb.ToString());
                        k = to + 1;
                    }
                }
                o.Write("</g>\n");
            }
        }
        Hair(behind: true);
        foreach (var c in scene.Colliders)
        {
            if (c.Kind != ColliderKind.Ellipsoid && c.Kind != ColliderKind.Sphere) continue;
            var wc = c.ToWorld(w.Head);
            var m = Map(wc.Center);
            float rx = (view == View.Front ? wc.Radii.X : wc.Radii.Z) * scale, ry = wc.Radii.Y * scale;
            o.Write(string.Create(ci, $"<ellipse cx=\"{m.X:F1}\" cy=\"{m.Y:F1}\" rx=\"{rx:F1}\" ry=\"{ry:F1}\" fill=\"#f1d9c4\" stroke=\"#c9a98e\"/>\n"));
        }
        if (meshHead != null) o.Write(Silhouette(meshHead, meshPose, Map, pixels));
        Hair(behind: false);
        if (title != null)
            o.Write($"<text x=\"10\" y=\"20\" font-family=\"sans-serif\" font-size=\"14\" fill=\"#333\">{System.Security.SecurityElement.Escape(title)}</text>\n");
        o.Write("</svg>\n");
    }

    /// <summary>
    /// A mesh head (placed by <paramref name="head"/>: the collider's pose) as one filled path: its triangles rasterised into
    /// cells of 3 pixels and written as horizontal runs, so a 25,000-triangle head costs a few kilobytes, not megabytes.
    /// </summary>
    private static string Silhouette(Meshes.TriangleMesh mesh, RigidTransform head, Func<Vector3, Vector2> map, int pixels)
    {
        const int cellPx = 3;
        int n = (pixels + cellPx - 1) / cellPx;
        var covered = new bool[n * n];
        var p = mesh.Positions; var idx = mesh.Indices;
        var screen = new Vector2[p.Length];
        for (int v = 0; v < p.Length; v++) screen[v] = map(head.TransformPoint(p[v])) / cellPx;
        for (int t = 0; t + 2 < idx.Length; t += 3)
        {
            Vector2 a = screen[idx[t]], b = screen[idx[t + 1]], c = screen[idx[t + 2]];
            float area = (b.X - a.X) * (c.Y - a.Y) - (b.Y - a.Y) * (c.X - a.X);
            if (!float.IsFinite(area) || MathF.Abs(area) < 1e-12f) continue;
            int x0 = Math.Max(0, (int)MathF.Floor(MathF.Min(a.X, MathF.Min(b.X, c.X)))), x1 = Math.Min(n - 1, (int)MathF.Ceiling(MathF.Max(a.X, MathF.Max(b.X, c.X))));
            int y0 = Math.Max(0, (int)MathF.Floor(MathF.Min(a.Y, MathF.Min(b.Y, c.Y)))), y1 = Math.Min(n - 1, (int)MathF.Ceiling(MathF.Max(a.Y, MathF.Max(b.Y, c.Y))));
            for (int y = y0; y <= y1; y++)
                for (int x = x0; x <= x1; x++)
                {
                    var q = new Vector2(x + 0.5f, y + 0.5f);
                    float e0 = ((b.X - a.X) * (q.Y - a.Y) - (b.Y - a.Y) * (q.X - a.X)) / area;
                    float e1 = ((c.X - b.X) * (q.Y - b.Y) - (c.Y - b.Y) * (q.X - b.X)) / area;
                    float e2 = ((a.X - c.X) * (q.Y - c.Y) - (a.Y - c.Y) * (q.X - c.X)) / area;
                    if (e0 >= 0f && e1 >= 0f && e2 >= 0f) covered[y * n + x] = true;
                }
        }
        var sb = new System.Text.StringBuilder("<path fill=\"#f1d9c4\" d=\"");
        var ci = CultureInfo.InvariantCulture;
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++)
            {
                if (!covered[y * n + x]) continue;
                int run = x;
                while (run + 1 < n && covered[y * n + run + 1]) run++;
                sb.Append(ci, $"M{x * cellPx} {y * cellPx}h{(run - x + 1) * cellPx}v{cellPx}h-{(run - x + 1) * cellPx}z");
                x = run;
            }
        sb.Append("\"/>\n");
        return sb.ToString();
    }

    public static void Write(string path, HairScene scene, View view, float extent = 0.6f, int pixels = 600, bool[]? highlight = null, string? title = null, int every = 1) =>
        SafeFile.Write(path, s =>
        {
            using var o = new StreamWriter(s, new System.Text.UTF8Encoding(false), 1 << 16, leaveOpen: true);
            Write(o, scene, view, extent, pixels, highlight, title, every);
        });
}
