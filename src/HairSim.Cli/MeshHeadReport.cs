using System.Globalization;
using System.Numerics;
using System.Text;
using HairSim;
using HairSim.Measurement;
using HairSim.Meshes;

namespace HairSim.Cli;

/// <summary>
/// The report's mesh-head section: penetration and error figures of the reference groom grown on the project's head
/// (<see cref="ProceduralHead"/>, 2.5 mm distance field) against the same groom on the ellipsoid head, after a head
/// shake, on the fast path (strand chunks) with the system-by-system path as a bit check.
/// </summary>
internal static class MeshHeadReport
{
    public static void Append(StringBuilder md, bool quick)
    {
        var groom = GroomSettings.Reference();
        if (quick) groom.SheetCount = 60;
        int shakeFrames = quick ? 60 : 180;
        md.Append("\n## Mesh head\n\n");
        md.Append(F($"The {(quick ? "quick run's smaller groom" : "reference groom")} ({groom.SheetCount} sheets × {groom.StrandsPerSheet} strands × {groom.ParticlesPerStrand} particles) grown on the project's head (`ProceduralHead`: the reference ellipsoid with 8 mm ears, nose and neck as separate parts, 2.5 mm distance field; hair collides with the mesh only) and on the ellipsoid head, after 1 s still and {shakeFrames / 60} s of head shake at 60 Hz, 4 substeps, fast path. Penetration: the deepest free particle inside the mesh (the ellipsoid); segments: the deepest of 7 points inside each segment (what a thin part between two particles would show); stretch: the largest segment length against its rest length at the end of the frame. The mesh head's run is repeated with strand chunks off (system by system): the two must give the same bits.\n\n"));
        md.Append("| head | deepest particle (mm) | particles inside | deepest segment point (mm) | max segment stretch | length / rest length | non-finite | same bits without chunks |\n|---|---:|---:|---:|---:|---:|---:|---|\n");
        var mesh = ProceduralHead.Create();
        var field = SignedDistanceField.Bake(mesh, 0.0025f);
        using var threads = ThreadDispatchers.CreateDefault();
        foreach (bool onMesh in new[] { true, false })
        {
            HairScene Build() => onMesh
                ? MeshScalp.BuildScene(mesh, field, new MeshGroomSettings
                {
                    SheetCount = groom.SheetCount, StrandsPerSheet = groom.StrandsPerSheet, ParticlesPerStrand = groom.ParticlesPerStrand,
                    StrandLength = groom.StrandLength, ScalpMaskThreshold = 0.5f,
                })
                : GroomBuilder.BuildScene(groom);
            var scene = Build();
            var plain = onMesh ? Build() : null;
            var sim = new HairSimulation(scene, dispatcher: threads);
            var simPlain = plain != null ? new HairSimulation(plain, dispatcher: threads) : null;
            if (simPlain != null) simPlain.Pipeline.UseStrandChunks = false;
            void Step(int f, RigidTransform head) { sim.Step(1f / 60f, head); simPlain?.Step(1f / 60f, head); }
            for (int f = 0; f < 60; f++) Step(f, RigidTransform.Identity);
            for (int f = 1; f <= shakeFrames; f++) Step(f, HeadMotion.Shake(f / 60f));
            var m = WorldMetrics.Measure(scene);
            string bits = plain == null ? "–" : scene.World.BitEquals(plain.World) ? "yes" : "**no**";
            md.Append(F($"| {(onMesh ? "mesh (ProceduralHead)" : "ellipsoid")} | {m.MaxPenetration * 1000:F3} | {m.ParticlesInside} | {DeepestSegmentPoint(scene) * 1000:F3} | {m.MaxEdgeStretch * 100:F1} % | {m.LengthRatio:F5} | {m.NonFinite} | {bits} |\n"));
        }
        md.Append("\nThe stretch on the mesh head is beside the ears (pushes out of a thin part do not keep lengths; the next substep's sweep restores them); speed: `bench` (mesh head against ellipsoid head, docs/meshes.md).\n");
    }

    /// <summary>The deepest of 7 inner points of every segment inside the head: the mesh's field, or the scene's colliders.</summary>
    private static double DeepestSegmentPoint(HairScene scene)
    {
        var w = scene.World;
        var mc = scene.GetComponent<MeshCollider>();
        var colliders = new Collider[scene.Colliders.Count];
        for (int c = 0; c < colliders.Length; c++) colliders[c] = scene.Colliders[c].ToWorld(w.Head);
        double deepest = 0;
        for (int s = 0; s < w.StrandCount; s++)
        {
            int first = w.StrandFirst[s];
            for (int i = first + 1; i < first + w.StrandParticleCount[s]; i++)
            {
                var a = w.GetPosition(i - 1); var b = w.GetPosition(i);
                for (int t = 1; t < 8; t++)
                {
                    var p = Vector3.Lerp(a, b, t / 8f);
                    if (mc != null) deepest = Math.Max(deepest, -mc.Field.Distance(mc.PoseFor(w.Head).InverseTransformPoint(p)));
                    foreach (var c in colliders) deepest = Math.Max(deepest, c.Penetration(p));
                }
            }
        }
        return deepest;
    }

    private static string F(FormattableString s) => s.ToString(CultureInfo.InvariantCulture);
}
