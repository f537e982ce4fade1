using System.Runtime.Intrinsics.X86;
using HairSim.Fast;
using HairSim.Measurement;

namespace HairSim.Tests.Fast;

public class PrefetcherTests
{
    [Theory]
    [InlineData(16, 4, 30)] // the reference strands, 4 substeps, a call per half of each swept row
    [InlineData(16, 1, 4)]  // one substep, a slice after each of four systems
    [InlineData(3, 4, 2)]
    [InlineData(64, 5, 126)]
    public void PacedCallsFetchEveryLineOfTheNextChunkOnce(int particles, int substeps, int callsPerSubstep)
    {
        if (!Sse.IsSupported) return; // prefetches are x86 hints; elsewhere nothing is fetched
        var g = CanonicalCases.SmallGroom(particles, 4, 32);
        var w = GroomBuilder.BuildScene(g, new SimulationSettings()).World;
        var kept = new ChunkConstantRows(ChunkFields.RestLength);
        kept.Fit(w);
        var p = new Prefetcher(w, 32, w.StrandFirst[32], particles, kept, []);
        // Positions, velocities, masses and rest lengths (the last two as kept in row layout): 8 fields of 32 strands' particles, in 64-byte lines.
        Assert.Equal(8 * 32 * particles * sizeof(float) / 64, p.Lines);
        int calls = substeps * callsPerSubstep;
        p.PerCall = (p.Lines + calls - 1) / calls;
        for (int c = 0; c < calls; c++)
        {
            int before = p.Issued;
            p.Next(p.PerCall);
            Assert.InRange(p.Issued - before, 0, p.PerCall); // small steps, never a burst
        }
        Assert.Equal(p.Lines, p.Issued);
        p.Next(100);
        Assert.Equal(p.Lines, p.Issued); // nothing past the chunk
    }

    [Fact]
    public void AtOneSubstepTheChunkAfterTheNextIsFetchedFromTheRowsOfTheNext()
    {
        if (!Sse.IsSupported) return;
        const int particles = 16, cells = 32 * particles;
        var g = CanonicalCases.SmallGroom(particles, 4, 32); // 128 strands: chunks from strands 0, 32, 64 and 96
        var w = GroomBuilder.BuildScene(g, new SimulationSettings()).World;
        var kept = new ChunkConstantRows(ChunkFields.RestLength);
        kept.Fit(w);
        // The next chunk from strand 32: the one after it (from strand 64) starts a chunk's cells on in the world's
        // arrays, and two fields' worth of cells on in the kept rows (masses and rest lengths side by side per chunk).
        var p = new Prefetcher(w, 32, w.StrandFirst[32], particles, kept, [], twoAhead: true);
        Assert.Equal(w.StrandFirst[64] - w.StrandFirst[32], cells);
        for (int f = 0; f < 6; f++) Assert.Equal(cells * sizeof(float), p.AheadBytes(f));
        for (int f = 6; f < 8; f++) Assert.Equal(2 * cells * sizeof(float), p.AheadBytes(f));
        // No chunk after the last but one: nothing fetched past the world's end.
        var last = new Prefetcher(w, 96, w.StrandFirst[96], particles, kept, [], twoAhead: true);
        Assert.Equal(w.ParticleCount, w.StrandFirst[96] + cells);
        for (int f = 0; f < 8; f++) Assert.Equal(0, last.AheadBytes(f));
        // Frames of more substeps fetch only the next chunk.
        var four = new Prefetcher(w, 32, w.StrandFirst[32], particles, kept, []);
        for (int f = 0; f < 8; f++) Assert.Equal(0, four.AheadBytes(f));
    }

    [Theory]
    [InlineData(1)]
    [InlineData(2)]
    [InlineData(4)]
    [InlineData(8)]
    public void AChunksPerStrandEntriesAreFetchedOnEveryLineTheyTouch(int size)
    {
        // Whatever the array's alignment: every 64-byte line holding one of the 32 entries holds a fetched one.
        for (int offset = 0; offset < 64; offset += size)
        {
            var touched = new HashSet<int>();
            for (int e = 0; e < 32; e++) touched.Add((offset + e * size) / 64);
            var fetched = new HashSet<int>();
            for (int k = 0; k < Prefetcher.StrandEntries(size); k++)
            {
                int e = Prefetcher.StrandEntry(k, size);
                Assert.InRange(e, 0, 31);
                fetched.Add((offset + e * size) / 64);
            }
            Assert.Equal(touched.OrderBy(x => x), fetched.OrderBy(x => x));
        }
        Assert.True(Prefetcher.StrandEntries(size) <= 32 * size / 64 + 2); // about a line each, not an entry each
    }

    [Fact]
    public void NothingIsFetchedPastTheWorldsEnd()
    {
        var g = CanonicalCases.SmallGroom(16, 1, 32);
        var w = GroomBuilder.BuildScene(g, new SimulationSettings()).World;
        // The chunk after the last one does not exist.
        var kept = new ChunkConstantRows(ChunkFields.RestLength);
        kept.Fit(w);
        var p = new Prefetcher(w, 32, w.ParticleCount, 16, kept, []);
        Assert.Equal(0, p.Lines);
        p.Next(10);
        Assert.Equal(0, p.Issued);
    }
}
