// The caches method's virtual area lights (VALs): RSM texels read from the maps, and the
// selection's random numbers. The GPU's copy of vpl_texel_area() (common/gi/vpl_source.c)
// and vpl_slot_random() (common/gi/vpl/vpl_select.c); compiled before the passes that use it.
uniform sampler2DArray u_rsm_position;   // w 1 where geometry
uniform sampler2DArray u_rsm_normal;     // unit normal turned to the light
uniform sampler2DArray u_rsm_flux;       // W reflected
uniform int u_rsm_size;

struct val {
    vec3 position;
    vec3 normal;
    vec3 flux;
    float area;
};

// q (a texel's position) lies on p's plane: within about 3 degrees of it, normals alike.
bool val_same_plane(vec4 p, vec3 np, vec4 q, vec3 nq)
{
    if (q.w == 0.0)
        return false;
    vec3 d = q.xyz - p.xyz;
    float len = length(d);
    return len > 0.0 && abs(dot(d, np)) <= 0.05 * len && dot(np, nq) > 0.99;
}

// Step to the neighbour on t's plane along axis (forward first); false when neither is.
bool val_step(ivec3 t, ivec2 axis, vec4 p, vec3 n, out vec3 step)
{
    for (int sign = 1; sign >= -1; sign -= 2) {
        ivec3 q = t + ivec3(sign * axis, 0);
        if (any(lessThan(q.xy, ivec2(0))) || any(greaterThanEqual(q.xy, ivec2(u_rsm_size))))
            continue;
        vec4 qp = texelFetch(u_rsm_position, q, 0);
        if (val_same_plane(p, n, qp, texelFetch(u_rsm_normal, q, 0).xyz)) {
            step = qp.xyz - p.xyz;
            return true;
        }
    }
    step = vec3(0.0);
    return false;
}

// Texel t (x, y, layer) as a VAL; flux 0 where no geometry or no light.
val val_fetch(ivec3 t)
{
    val v;
    vec4 p = texelFetch(u_rsm_position, t, 0);
    v.position = p.xyz;
    v.normal = texelFetch(u_rsm_normal, t, 0).xyz;
    v.flux = p.w == 0.0 ? vec3(0.0) : max(texelFetch(u_rsm_flux, t, 0).rgb, vec3(0.0));
    vec3 a, b;
    bool ha = val_step(t, ivec2(1, 0), p, v.normal, a);
    bool hb = val_step(t, ivec2(0, 1), p, v.normal, b);
    v.area = ha && hb ? length(cross(a, b)) : (ha ? dot(a, a) : (hb ? dot(b, b) : 0.0));
    return v;
}

// Wellons' lowbias32, and the fixed random number in [0, 1) of slot i (dimension 0).
uint val_mix32(uint x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

float val_slot_random(uint seed, int i)
{
    uint h = val_mix32(val_mix32(seed ^ 0x9e3779b9u) + uint(i));
    return float(h >> 8) * (1.0 / 16777216.0);
}
