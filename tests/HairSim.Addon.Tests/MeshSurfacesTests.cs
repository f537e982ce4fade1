using System.Numerics;
using HairSheet.Logic;
using HairSim.Meshes;
using Xunit;

namespace HairSim.Addon.Tests;

/// <summary>A Godot mesh's arrays become a head-space mesh whose distance field is negative inside, not outside.</summary>
public sealed class MeshSurfacesTests
{
    [Fact]
    public void ClockwiseGodotSurfacesBecomeAnOutwardFacingMeshInHeadSpace()
    {
        // A sphere as Godot would hold it: HairSim's counter-clockwise sphere with every triangle's winding reversed.
        var ccw = TriangleMesh.Ellipsoid(Vector3.Zero, new Vector3(0.1f), 24, 48);
        var cw = (int[])ccw.Indices.Clone();
        for (int t = 0; t < cw.Length; t += 3) (cw[t + 1], cw[t + 2]) = (cw[t + 2], cw[t + 1]);
        var toHead = Matrix4x4.CreateTranslation(0, 0.5f, 0);
        var mesh = MeshSurfaces.ToHeadSpace([new MeshSurfaces.Surface(ccw.Positions, cw, null)], toHead);
        var field = SignedDistanceField.Bake(mesh, 0.005f);
        Assert.True(field.Distance(new Vector3(0, 0.5f, 0)) < -0.05f, "the centre is inside");
        Assert.True(field.Distance(new Vector3(0, 0.5f, 0.11f)) > 0f, "just outside the surface is outside");
        Assert.Equal(ccw.TriangleCount, mesh.TriangleCount);
    }

    [Fact]
    public void FieldsStoredAsArraysComeBackBitForBitAndCorruptStoresAreRefused()
    {
        var field = SignedDistanceField.Bake(TriangleMesh.Box(new Vector3(-0.02f), new Vector3(0.02f)), 0.004f);
        var stored = field.CopyDistances();
        var back = SignedDistanceField.FromData(field.Origin, field.CellSize, field.Nx, field.Ny, field.Nz, stored);
        Assert.Equal(field.Distance(new Vector3(0.01f, 0.003f, -0.007f)), back.Distance(new Vector3(0.01f, 0.003f, -0.007f)));
        Assert.Throws<ArgumentException>(() => SignedDistanceField.FromData(field.Origin, field.CellSize, field.Nx, field.Ny, field.Nz, stored[1..]));
        stored[3] = float.NaN;
        Assert.Throws<ArgumentException>(() => SignedDistanceField.FromData(field.Origin, field.CellSize, field.Nx, field.Ny, field.Nz, stored));
        Assert.Throws<ArgumentException>(() => MeshSurfaces.ToHeadSpace([new MeshSurfaces.Surface([Vector3.Zero, Vector3.UnitX], [0, 1], null)], Matrix4x4.Identity));
    }
}
