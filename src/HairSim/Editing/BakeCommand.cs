namespace HairSim.Editing;

/// <summary>Current positions become the rest pose (head space) and rest shape of some strands.</summary>
internal sealed class BakeCommand : EditCommand
{
    public BakeCommand(HairWorld world, int[] strands) : base(world, "Bake rest pose", strands) { }

    protected override void Execute(HairWorld w)
    {
        var head = w.Head;
        foreach (int s in Strands)
        {
            int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
            for (int i = first; i < first + n; i++)
            {
                if (w.InvMass[i] == 0f) continue;
                var r = head.InverseTransformPoint(w.GetPosition(i));
                w.RestX[i] = r.X; w.RestY[i] = r.Y; w.RestZ[i] = r.Z;
            }
            RestShape.SetFromRestPose(w, s);
        }
    }
}
