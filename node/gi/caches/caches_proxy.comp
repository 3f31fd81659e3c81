// Proxy lights (cache_proxy_gather()): per cache, the irradiance of every VAL, the proxy's
// position and extent. VALs come from the list (the emitters, then the selection), or,
// with ALL_TEXELS defined, the emitters and then every RSM texel with weight 1 (plain
// LightSkin). A work group shares each tile of VALs. One dispatch sums VALs [u_begin,
// u_end) into each cache's running sums (after the proxies in the same buffer), the last
// one makes the proxy: a loop of a few thousand VALs per dispatch (llvmpipe ends any
// shader loop after 65535 iterations; a GPU's watchdog ends long dispatches).
// With GLOSSY defined, the glossy proxy too (cache_glossy_gather()): the same sums with each
// VAL's weight times the cache's specular lobe towards u_eye, in the buffer's glossy part.
#define TILE 64
layout(local_size_x = TILE) in;

layout(std430, binding = 0) readonly buffer Caches { vec4 caches[]; };   // position+area, normal
layout(std430, binding = 1) buffer Proxies { vec4 proxies[]; }; // position+radius, E+visibility
                                                                // per cache, then 3 sums; the
                                                                // glossy part from GLOSSY_PART
                                                                // caches: the same, then the
                                                                // lobe exponent
layout(std430, binding = 2) readonly buffer Vals { vec4 vals[]; };       // position+area, normal, flux

uniform int u_caches;
uniform int u_vals;      // in the list (ALL_TEXELS: the emitters)
uniform int u_texels;    // ALL_TEXELS: RSM texels after them (layers x size^2)
uniform int u_begin, u_end, u_last;
#ifdef GLOSSY
uniform vec3 u_eye;
#endif

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

// The proxy from its sums: position + radius (the spread) and the summed light.
void place(int c, int at, vec3 p, vec3 e, float sw, vec3 m1, vec3 m2, float scale)
{
    vec3 mean = sw > 0.0 ? m1 / sw : vec3(0.0);
    vec3 var = sw > 0.0 ? max(m2 / sw - mean * mean, vec3(0.0)) : vec3(0.0);
    float radius = 2.0 * sqrt(max(var.x, max(var.y, var.z)));
    proxies[at + 2 * c] = vec4(p + mean, radius);
    proxies[at + 2 * c + 1] = vec4(sw > 0.0 ? e * scale : vec3(0.0), 1.0);
}

// The running sums after a dispatch (slot: their first vec4).
void keep(int slot, vec3 e, float sw, vec3 m1, vec3 m2)
{
    proxies[slot] = vec4(e, sw);
    proxies[slot + 1] = vec4(m1, 0.0);
    proxies[slot + 2] = vec4(m2, 0.0);
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
#ifdef GLOSSY
    int part = GLOSSY_PART * u_caches, gsums = part + 2 * u_caches + 3 * self;
    vec3 view = u_eye - p;
    view = dot(view, view) > 0.0 ? normalize(view) : n;
    float m = proxies[part + 5 * u_caches + self].x;
    vec3 ge = vec3(0.0), g1 = vec3(0.0), g2 = vec3(0.0);
    float gw = 0.0;
    if (u_begin > 0) {
        vec4 a = proxies[gsums];
        ge = a.rgb;
        gw = a.w;
        g1 = proxies[gsums + 1].xyz;
        g2 = proxies[gsums + 2].xyz;
    }
#endif
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
#ifdef GLOSSY
            float lobe = specular_between(m, n, view, d / sqrt(r2));
            float wg = lobe * w;
            gw += wg;
            ge += lobe * f * flux;
            g1 += wg * d;
            g2 += wg * d * d;
#endif
        }
        barrier();
    }
    if (c >= u_caches)
        return;
    if (u_last == 0) {
        keep(sums, e, sw, m1, m2);
#ifdef GLOSSY
        keep(gsums, ge, gw, g1, g2);
#endif
        return;
    }
    place(c, 0, p, e, sw, m1, m2, 1.0);
#ifdef GLOSSY
    // E_g = L_g / f_s towards the proxy, the denominator at least the lobe's mean
    vec3 to_proxy = gw > 0.0 ? g1 / gw : vec3(0.0);
    to_proxy = dot(to_proxy, to_proxy) > 0.0 ? normalize(to_proxy) : n;
    float fp = max(specular_between(m, n, view, to_proxy), gw / max(sw, 1e-30));
    place(c, part, p, ge, gw, g1, g2, 1.0 / fp);
#endif
}
