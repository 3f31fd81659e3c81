// Proxy lights (cache_proxy_gather()): per cache, the irradiance of every VAL, the proxy's
// position and extent. VALs come from the list (the emitters, then the selection), or,
// with ALL_TEXELS defined, the emitters and then every RSM texel with weight 1 (plain
// LightSkin). A work group shares each tile of VALs. One dispatch sums VALs [u_begin,
// u_end) into each cache's running sums (after the proxies in the same buffer), the last
// one makes the proxy: a loop of a few thousand VALs per dispatch (llvmpipe ends any
// shader loop after 65535 iterations; a GPU's watchdog ends long dispatches).
#define TILE 64
layout(local_size_x = TILE) in;

layout(std430, binding = 0) readonly buffer Caches { vec4 caches[]; };   // position+area, normal
layout(std430, binding = 1) buffer Proxies { vec4 proxies[]; }; // position+radius, E+visibility
                                                                // per cache, then 3 sums
layout(std430, binding = 2) readonly buffer Vals { vec4 vals[]; };       // position+area, normal, flux

uniform int u_caches;
uniform int u_vals;      // in the list (ALL_TEXELS: the emitters)
uniform int u_texels;    // ALL_TEXELS: RSM texels after them (layers x size^2)
uniform int u_begin, u_end, u_last;

shared vec4 tile_position[TILE], tile_normal[TILE], tile_flux[TILE];

void load(int j, int slot)
{
#ifdef ALL_TEXELS
    if (j >= u_vals) {
        int t = j - u_vals, per = u_rsm_size * u_rsm_size;
        val v = val_fetch(ivec3(t % u_rsm_size, t / u_rsm_size % u_rsm_size, t / per));
        tile_position[slot] = vec4(v.position, v.area);
        tile_normal[slot] = vec4(v.normal, 0.0);
        tile_flux[slot] = vec4(v.flux, 0.0);
        return;
    }
#endif
    tile_position[slot] = vals[3 * j];
    tile_normal[slot] = vals[3 * j + 1];
    tile_flux[slot] = vals[3 * j + 2];
}

void main()
{
    int c = int(gl_GlobalInvocationID.x), slot = int(gl_LocalInvocationID.x);
    int self = min(c, u_caches - 1), sums = 2 * u_caches + 3 * self;
    vec3 p = caches[2 * self].xyz, n = caches[2 * self + 1].xyz;
    vec3 e = vec3(0.0), m1 = vec3(0.0), m2 = vec3(0.0);
    float sw = 0.0;
    if (u_begin > 0) {
        vec4 a = proxies[sums];
        e = a.rgb;
        sw = a.w;
        m1 = proxies[sums + 1].xyz;
        m2 = proxies[sums + 2].xyz;
    }
    for (int base = u_begin; base < u_end; base += TILE) {
        if (base + slot < u_end)
            load(base + slot, slot);
        else
            tile_flux[slot] = vec4(0.0);
        barrier();
        for (int k = 0; k < TILE; k++) {
            vec3 flux = tile_flux[k].rgb;
            vec3 d = tile_position[k].xyz - p;
            float r2 = dot(d, d);
            float cos_c = dot(n, d), cos_l = -dot(tile_normal[k].xyz, d);
            if (!(r2 > 0.0) || !(cos_c > 0.0 && cos_l > 0.0))
                continue;
            float f = cos_c * cos_l / (r2 * (tile_position[k].w + PI * r2));
            float w = f * (flux.r + flux.g + flux.b);
            sw += w;
            e += f * flux;
            m1 += w * d;
            m2 += w * d * d;
        }
        barrier();
    }
    if (c >= u_caches)
        return;
    if (u_last == 0) {
        proxies[sums] = vec4(e, sw);
        proxies[sums + 1] = vec4(m1, 0.0);
        proxies[sums + 2] = vec4(m2, 0.0);
        return;
    }
    vec3 mean = sw > 0.0 ? m1 / sw : vec3(0.0);
    vec3 var = sw > 0.0 ? max(m2 / sw - mean * mean, vec3(0.0)) : vec3(0.0);
    float radius = 2.0 * sqrt(max(var.x, max(var.y, var.z)));
    proxies[2 * c] = vec4(p + mean, radius);
    proxies[2 * c + 1] = vec4(sw > 0.0 ? e : vec3(0.0), 1.0);
}
