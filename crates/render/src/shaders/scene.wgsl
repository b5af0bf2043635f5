// Scene shaders: flat-shaded faces, screen-space wide lines, point markers.
// Colours arrive sRGB-encoded (Unorm8x4); lighting is done in linear space and the result is written
// sRGB-encoded again into a *Unorm* target. Depth is reverse-Z (1 near, 0 far).

struct Globals {
    view_proj: mat4x4<f32>,
    // xyz: eye position; w: 0 for a perspective camera, else the orbit distance in normalized
    // depth units of an orthographic camera (depth biases are added, not scaled, there).
    eye: vec4<f32>,
    // xyz: unit direction towards the light (a headlight slightly above and left of the eye), w: ambient.
    light: vec4<f32>,
    // x, y: target size in pixels; z: relative depth bias of lines; w: relative depth bias of points.
    viewport: vec4<f32>,
};

@group(0) @binding(0) var<uniform> g: Globals;

const FLAG_ON_TOP: u32 = 1u;
const FLAG_DISC: u32 = 2u;

fn srgb_to_linear(c: vec3<f32>) -> vec3<f32> {
    let lo = c / 12.92;
    let hi = pow((c + vec3<f32>(0.055)) / 1.055, vec3<f32>(2.4));
    return select(hi, lo, c <= vec3<f32>(0.04045));
}

fn linear_to_srgb(c: vec3<f32>) -> vec3<f32> {
    let lo = c * 12.92;
    let hi = 1.055 * pow(max(c, vec3<f32>(0.0)), vec3<f32>(1.0 / 2.4)) - vec3<f32>(0.055);
    return select(hi, lo, c <= vec3<f32>(0.0031308));
}

// ---------------------------------------------------------------------------------------- faces

struct FaceOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) color: vec4<f32>,
};

// Relative depth bias of one depth layer of faces (scene.rs: FACE_LAYER_BIAS).
const FACE_LAYER_BIAS: f32 = 2e-5;

@vertex
fn vs_face(
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) color: vec4<f32>,
    @location(3) depth_layer: u32,
) -> FaceOut {
    var out: FaceOut;
    // Coincident surfaces of different layers: the higher layer is nudged towards the eye.
    out.clip = apply_depth(g.view_proj * vec4<f32>(position, 1.0), 0u, f32(depth_layer) * FACE_LAYER_BIAS);
    out.world = position;
    out.normal = normal;
    out.color = color;
    return out;
}

@fragment
fn fs_face(in: FaceOut) -> @location(0) vec4<f32> {
    let to_eye = normalize(g.eye.xyz - in.world);
    var n = in.normal;
    let len = length(n);
    if (len < 1e-6) {
        n = to_eye; // degenerate face: fully lit
    } else {
        n = n / len;
    }
    // Both sides lit: turn the normal towards the viewer.
    if (dot(n, to_eye) < 0.0) {
        n = -n;
    }
    let ambient = g.light.w;
    let diffuse = max(dot(n, g.light.xyz), 0.0);
    let base = srgb_to_linear(in.color.rgb);
    let lit = base * (ambient + (1.0 - ambient) * diffuse);
    return vec4<f32>(linear_to_srgb(lit), in.color.a);
}

// ---------------------------------------------------------------------------------------- lines

struct FlatOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) color: vec4<f32>,
    // Position inside the quad, -1..1 on both axes (used by discs).
    @location(1) uv: vec2<f32>,
    @location(2) @interpolate(flat) flags: u32,
};

fn to_pixels(c: vec4<f32>) -> vec2<f32> {
    return c.xy / c.w * 0.5 * g.viewport.xy;
}

fn apply_depth(c: vec4<f32>, flags: u32, bias: f32) -> vec4<f32> {
    var out = c;
    if ((flags & FLAG_ON_TOP) != 0u) {
        out.z = out.w; // depth 1: nearest possible, passes against everything
    } else if (g.eye.w > 0.0) {
        // Orthographic (linear depth): towards the eye by `bias` orbit distances.
        out.z = min(out.z + bias * g.eye.w * out.w, out.w);
    } else {
        // Reverse-Z: scaling z moves the point towards the eye by a relative amount along its ray.
        out.z = min(out.z * (1.0 + bias), out.w);
    }
    return out;
}

@vertex
fn vs_line(
    @builtin(vertex_index) vi: u32,
    @location(0) a: vec3<f32>,
    @location(1) b: vec3<f32>,
    @location(2) color: vec4<f32>,
    @location(3) width: f32,
    @location(4) flags: u32,
) -> FlatOut {
    var out: FlatOut;
    out.color = color;
    out.flags = flags;
    var ca = g.view_proj * vec4<f32>(a, 1.0);
    var cb = g.view_proj * vec4<f32>(b, 1.0);
    // Clip against the near plane (reverse-Z: inside when z <= w).
    let da = ca.w - ca.z;
    let db = cb.w - cb.z;
    if (da < 0.0 && db < 0.0) {
        out.clip = vec4<f32>(0.0, 0.0, -1.0, 1.0); // outside: degenerate, culled
        out.uv = vec2<f32>(0.0);
        return out;
    }
    if (da < 0.0) {
        ca = mix(ca, cb, da / (da - db));
    } else if (db < 0.0) {
        cb = mix(cb, ca, db / (db - da));
    }
    let sa = to_pixels(ca);
    let sb = to_pixels(cb);
    var dir = sb - sa;
    let len = length(dir);
    if (len < 1e-6) {
        dir = vec2<f32>(1.0, 0.0);
    } else {
        dir = dir / len;
    }
    let nrm = vec2<f32>(-dir.y, dir.x);
    // Two triangles: corners (end, side) = (0,-1) (1,-1) (1,1) / (0,-1) (1,1) (0,1).
    var ends = array<u32, 6>(0u, 1u, 1u, 0u, 1u, 0u);
    var sides = array<f32, 6>(-1.0, -1.0, 1.0, -1.0, 1.0, 1.0);
    let end = ends[vi];
    let side = sides[vi];
    var c = ca;
    var along = -1.0;
    if (end == 1u) {
        c = cb;
        along = 1.0;
    }
    let half = 0.5 * width;
    // Square caps (half a width past each end) close the gaps at polyline joints.
    let offset_px = nrm * side * half + dir * along * half;
    let offset_clip = offset_px / (0.5 * g.viewport.xy) * c.w;
    out.clip = apply_depth(vec4<f32>(c.xy + offset_clip, c.z, c.w), flags, g.viewport.z);
    out.uv = vec2<f32>(along, side);
    return out;
}

@fragment
fn fs_flat(in: FlatOut) -> @location(0) vec4<f32> {
    if ((in.flags & FLAG_DISC) != 0u && dot(in.uv, in.uv) > 1.0) {
        discard;
    }
    return in.color;
}

// ---------------------------------------------------------------------------------------- points

@vertex
fn vs_point(
    @builtin(vertex_index) vi: u32,
    @location(0) position: vec3<f32>,
    @location(1) color: vec4<f32>,
    @location(2) size: f32,
    @location(3) flags: u32,
) -> FlatOut {
    var out: FlatOut;
    out.color = color;
    out.flags = flags;
    let c = g.view_proj * vec4<f32>(position, 1.0);
    if (c.w - c.z < 0.0) {
        out.clip = vec4<f32>(0.0, 0.0, -1.0, 1.0); // in front of the near plane: culled
        out.uv = vec2<f32>(0.0);
        return out;
    }
    var xs = array<f32, 6>(-1.0, 1.0, 1.0, -1.0, 1.0, -1.0);
    var ys = array<f32, 6>(-1.0, -1.0, 1.0, -1.0, 1.0, 1.0);
    let uv = vec2<f32>(xs[vi], ys[vi]);
    let offset_clip = uv * (0.5 * size) / (0.5 * g.viewport.xy) * c.w;
    out.clip = apply_depth(vec4<f32>(c.xy + offset_clip, c.z, c.w), flags, g.viewport.w);
    out.uv = uv;
    return out;
}
