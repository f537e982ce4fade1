using System.Numerics;

namespace HairSim.Tests.Core;

public class GroomBuilderTests
{
    [Fact]
    public void BuildsTheReferenceSceneOfTheSource()
    {
        var g = GroomSettings.Reference();
        var w = GroomBuilder.Build(g);
        Assert.Equal(435, w.SheetCount);
        Assert.Equal(435 * 40, w.StrandCount);
        Assert.Equal(435 * 40 * 16, w.ParticleCount);
        Assert.Equal(0, w.CountNonFinite());
        // Roots sit on the scalp (just outside the ellipsoid), every segment has its rest length, no particle is inside the head.
        var head = Collider.Ellipsoid(g.HeadCenter, g.HeadRadii);
        for (int s = 0; s < w.StrandCount; s += 97)
        {
            var root = w.GetPosition(w.RootIndex(s));
            Assert.Equal(0f, head.Penetration(root));
            var l = root / g.HeadRadii;
            Assert.InRange(l.Length(), 1f, 1.05f);
            for (int k = 1; k < g.ParticlesPerStrand; k++)
            {
                int i = w.StrandFirst[s] + k;
                Assert.Equal(w.RestLength[i], Vector3.Distance(w.GetPosition(i), w.GetPosition(i - 1)), 5);
                Assert.Equal(0f, head.Penetration(w.GetPosition(i)));
            }
        }
        Assert.Equal(g.StrandLength * w.StrandCount, w.TotalRestLength(), 0);
    }

    [Fact]
    public void DrapedGroomFallsAndUndrapedStandsOutAlongTheNormal()
    {
        var g = TestWorlds.SmallGroom();
        var flat = g.Clone(); flat.Drape = 0f;
        var draped = GroomBuilder.Build(g);
        var straight = GroomBuilder.Build(flat);
        int falling = 0;
        for (int s = 0; s < draped.StrandCount; s++)
        {
            var root = draped.GetPosition(draped.RootIndex(s));
            var tip = draped.GetPosition(draped.TipIndex(s));
            // Combed down: every tip ends lower than its root, most by more than half the length.
            Assert.True(tip.Y < root.Y, $"strand {s}: the tip is not below the root");
            if (root.Y - tip.Y > 0.5f * g.StrandLength) falling++;
            // Drape 0: the source's groom, a straight line along the normal of the full length.
            var r0 = straight.GetPosition(straight.RootIndex(s));
            Assert.Equal(g.StrandLength, Vector3.Distance(r0, straight.GetPosition(straight.TipIndex(s))), 4);
        }
        Assert.True(falling > draped.StrandCount / 2, $"only {falling} of {draped.StrandCount} strands fall more than half their length");
    }

    [Fact]
    public void RootsAreJitteredNotOnAGrid()
    {
        var g = TestWorlds.SmallGroom();
        var even = g.Clone(); even.RootJitter = 0;
        var a = GroomBuilder.Build(g); var b = GroomBuilder.Build(even);
        // Same sheet layout, different roots: the jitter moved every strand's root a little, none a lot.
        float spacingSum = 0;
        for (int s = 0; s < a.StrandCount; s++)
        {
            float d = Vector3.Distance(a.GetPosition(a.RootIndex(s)), b.GetPosition(b.RootIndex(s)));
            Assert.True(d < 0.03f);
            spacingSum += d;
        }
        Assert.True(spacingSum / a.StrandCount > 1e-4f);
    }

    [Fact]
    public void NoRootIsOnTheFace()
    {
        var g = GroomSettings.Reference();
        var w = GroomBuilder.Build(g);
        for (int s = 0; s < w.StrandCount; s++)
        {
            var d = Vector3.Normalize(w.GetRest(w.RootIndex(s)) - g.HeadCenter);
            // The forehead limit: nothing lower than ScalpAngleFront (+ sheet spread) at the front.
            if (d.Z > 0.9f) Assert.True(MathF.Acos(d.Y) < g.ScalpAngleFront + 0.35f);
        }
    }
}
