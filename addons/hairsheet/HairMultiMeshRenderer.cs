using Godot;
using HairSheet.Logic;
using HairSim;

namespace HairSheet;

/// <summary>
/// Draws a HairSystem3D's render strands with one MultiMesh. Two layouts (see docs/godot.md for the
/// measurements behind the default): PositionTexture (one ribbon per strand, positions from an RGBAF texture;
/// per frame one texture upload) and SegmentInstances (one instance per segment; per frame one
/// MultimeshSetBuffer). Buffers are built once per scene and reused; CustomAabb is set from the strands so
/// the engine never recomputes bounds; VisibleInstanceCount hides segments removed by cuts. Positions are in
/// world space, so this node is top-level at the origin.
/// </summary>
[Tool]
[GlobalClass]
public partial class HairMultiMeshRenderer : MultiMeshInstance3D
{
    private const string DefaultShaderPath = "res://addons/hairsheet/shaders/hair_strand.gdshader";

    private StrandRenderLayout _layout = StrandRenderLayout.PositionTexture;
    private float _specularPower = 80f;
    private float _specularStrength = 0.35f;
    private Shader? _strandShader;
    private MultiMesh? _multiMesh;
    private ShaderMaterial? _material;
    private SegmentInstanceBuffer? _segments;
    private PositionTextureBuffer? _texture;
    private Image? _image;
    private ImageTexture? _positions;
    private RenderStrands? _bound;
    private StrandLook _look = StrandLook.Default;
    private Color _rootColor = new(0.16f, 0.10f, 0.06f), _tipColor = new(0.45f, 0.32f, 0.20f);

    [Export] public StrandRenderLayout Layout { get => _layout; set { _layout = value; Rebind(); } }
    /// <summary>The strand shader; empty = the addon's hair_strand.gdshader. A change rebuilds the material at once.</summary>
    [Export] public Shader? StrandShader { get => _strandShader; set { _strandShader = value; Rebind(); } }
    [Export(PropertyHint.Range, "1,512,1")] public float SpecularPower { get => _specularPower; set { _specularPower = value; _material?.SetShaderParameter("specular_power", value); } }
    [Export(PropertyHint.Range, "0,2,0.01")] public float SpecularStrength { get => _specularStrength; set { _specularStrength = value; _material?.SetShaderParameter("specular_strength", value); } }

    /// <summary>Bytes sent to the engine by the last Render call.</summary>
    public long LastUploadBytes { get; private set; }

    /// <summary>
    /// The MultiMesh, material and bounds are generated from the hair every time the scene opens: they are never
    /// written to the scene file (in the editor this [Tool] node assigns them, and a saved demo.tscn held the whole
    /// render state, ≈ 550k floats and a float texture, for the reference groom).
    /// </summary>
    public override void _ValidateProperty(Godot.Collections.Dictionary property)
    {
        base._ValidateProperty(property);
        var name = property["name"].AsStringName();
        if (name == MultiMeshInstance3D.PropertyName.Multimesh || name == GeometryInstance3D.PropertyName.MaterialOverride
            || name == GeometryInstance3D.PropertyName.CustomAabb)
            property["usage"] = (long)(property["usage"].As<PropertyUsageFlags>() & ~PropertyUsageFlags.Storage);
    }

    public override void _Ready()
    {
        TopLevel = true;
        GlobalTransform = Transform3D.Identity;
        CastShadow = ShadowCastingSetting.On;
    }

    /// <summary>Allocates every buffer for a scene's render output (called when the hair node rebuilds its scene).</summary>
    public void Bind(RenderStrands strands, StrandLook look, Color rootColor, Color tipColor)
    {
        _bound = strands;
        _look = look;
        _rootColor = rootColor;
        _tipColor = tipColor;
        Rebind();
    }

    public void SetColors(Color root, Color tip)
    {
        _rootColor = root; _tipColor = tip;
        _material?.SetShaderParameter("root_color", root);
        _material?.SetShaderParameter("tip_color", tip);
    }

    private void Rebind()
    {
        if (_bound == null) return;
        var rs = _bound;
        var mm = new MultiMesh();
        // Format and flags first: they can only change while the instance count is 0.
        mm.TransformFormat = MultiMesh.TransformFormatEnum.Transform3D;
        mm.UseColors = false;
        mm.UseCustomData = true;
        _material = new ShaderMaterial { Shader = _strandShader ?? GD.Load<Shader>(DefaultShaderPath) };
        _segments = null; _texture = null; _image = null; _positions = null;
        if (_layout == StrandRenderLayout.SegmentInstances)
        {
            _segments = new SegmentInstanceBuffer(rs, useColors: false, useCustomData: true, _look);
            mm.Mesh = ToArrayMesh(StrandRibbonMesh.Segment());
            mm.InstanceCount = _segments.MaxInstances;
            _material.SetShaderParameter("positions_from_texture", false);
        }
        else
        {
            _texture = new PositionTextureBuffer(rs, _look);
            mm.Mesh = ToArrayMesh(StrandRibbonMesh.Strand(rs.Stride));
            mm.InstanceCount = _texture.InstanceCount;
            // Static per-strand data: uploaded once here, never per frame.
            RenderingServer.MultimeshSetBuffer(mm.GetRid(), _texture.InstanceBuffer);
            _texture.Fill(rs);
            _image = Image.CreateFromData(_texture.Width, _texture.Height, false, Image.Format.Rgbaf, _texture.TexelBytes);
            _positions = ImageTexture.CreateFromImage(_image);
            _material.SetShaderParameter("positions_from_texture", true);
            _material.SetShaderParameter("positions", _positions);
            _material.SetShaderParameter("strand_stride", rs.Stride);
            _material.SetShaderParameter("strands_per_row", _texture.StrandsPerRow);
        }
        _material.SetShaderParameter("root_width", _look.RootWidth);
        _material.SetShaderParameter("tip_width", _look.TipWidth);
        _material.SetShaderParameter("specular_power", _specularPower);
        _material.SetShaderParameter("specular_strength", _specularStrength);
        SetColors(_rootColor, _tipColor);
        _multiMesh = mm;
        Multimesh = mm;
        MaterialOverride = _material;
        Render(rs);
    }

    /// <summary>Refills the reused buffers from the render strands and uploads them in one call. No managed allocation.</summary>
    public void Render(RenderStrands strands)
    {
        if (!ReferenceEquals(strands, _bound) || _multiMesh == null) return;
        var rid = _multiMesh.GetRid();
        if (_segments != null)
        {
            _segments.Fill(strands);
            RenderingServer.MultimeshSetBuffer(rid, _segments.Buffer);
            _multiMesh.VisibleInstanceCount = _segments.VisibleInstances;
            _multiMesh.CustomAabb = _segments.Bounds.ToAabb();
            LastUploadBytes = _segments.BytesPerUpload;
        }
        else if (_texture != null && _image != null && _positions != null)
        {
            _texture.Fill(strands);
            _image.SetData(_texture.Width, _texture.Height, false, Image.Format.Rgbaf, _texture.TexelBytes);
            _positions.Update(_image);
            _multiMesh.CustomAabb = _texture.Bounds.ToAabb();
            LastUploadBytes = _texture.BytesPerUpload;
        }
    }

    private static ArrayMesh ToArrayMesh(StrandRibbonMesh m)
    {
        int n = m.VertexCount;
        var vertices = new Vector3[n];
        var normals = new Vector3[n];
        var uvs = new Vector2[n];
        var tangents = new float[n * 4];
        for (int i = 0; i < n; i++)
        {
            vertices[i] = new Vector3(m.Positions[3 * i], m.Positions[3 * i + 1], m.Positions[3 * i + 2]);
            normals[i] = Vector3.Back;
            uvs[i] = new Vector2(m.Uvs[2 * i], m.Uvs[2 * i + 1]);
            tangents[4 * i + 1] = 1f;   // +Y: along the strand
            tangents[4 * i + 3] = 1f;
        }
        var arrays = new Godot.Collections.Array();
        arrays.Resize((int)Mesh.ArrayType.Max);
        arrays[(int)Mesh.ArrayType.Vertex] = vertices;
        arrays[(int)Mesh.ArrayType.Normal] = normals;
        arrays[(int)Mesh.ArrayType.Tangent] = tangents;
        arrays[(int)Mesh.ArrayType.TexUV] = uvs;
        arrays[(int)Mesh.ArrayType.Index] = m.Indices;
        var mesh = new ArrayMesh();
        mesh.AddSurfaceFromArrays(Mesh.PrimitiveType.Triangles, arrays);
        return mesh;
    }
}
