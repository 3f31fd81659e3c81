// Occlusion of each cache's proxy light by the other caches' disks (cache_occlusion()):
// the proxy's sphere and each nearer cache's disk projected onto the unit sphere and down
// onto the unit disk around the cache's normal, as squares of the same area; the overlaps
// over the proxy's square is the share blocked. Scales the proxy's irradiance. Caches
// [u_begin, u_end) per dispatch, the sum kept after the proxies' running sums (see
// caches_proxy.comp); the last applies it, with GLOSSY defined to the glossy proxy too (its
// own position is not tested: the diffuse proxy's visibility stands for it).
#define TILE 64
layout(local_size_x = TILE) in;

layout(std430, binding = 0) readonly buffer Caches { vec4 caches[]; };
layout(std430, binding = 1) buffer Proxies { vec4 proxies[]; };

uniform int u_caches;
uniform int u_begin, u_end, u_last;

shared vec4 tile_position[TILE], tile_normal[TILE];

float overlap(vec2 a, float sa, vec2 b, float sb)
{
    vec2 lo = max(a - 0.5 * sa, b - 0.5 * sb), hi = min(a + 0.5 * sa, b + 0.5 * sb);
    vec2 o = max(hi - lo, vec2(0.0));
    return o.x * o.y;
}

void main()
{
    int c = int(gl_GlobalInvocationID.x), slot = int(gl_LocalInvocationID.x);
    int self = min(c, u_caches - 1);
    vec3 p = caches[2 * self].xyz, n = caches[2 * self + 1].xyz;
    vec4 proxy = proxies[2 * self];
    vec3 v = proxy.xyz - p;
    float d = length(v);
    vec3 w = d > 0.0 ? v / d : n;
    float cos_p = dot(n, w);
    // Duff et al.'s basis around n, as vec3_basis()
    float sign = n.z >= 0.0 ? 1.0 : -1.0, ba = -1.0 / (sign + n.z), bb = n.x * n.y * ba;
    vec3 t1 = vec3(1.0 + sign * n.x * n.x * ba, sign * bb, -sign * n.x);
    vec3 t2 = vec3(bb, sign + n.y * n.y * ba, -n.y);
    float radius = min(proxy.w, 0.9 * d), s = d > 0.0 ? radius / d : 0.0;
    float square_p = 2.0 * PI * (1.0 - sqrt(1.0 - s * s)) * cos_p;
    bool lit_cache = c < u_caches && d > 0.0 && cos_p > 0.0 && square_p > 0.0;
    vec2 cp = vec2(dot(w, t1), dot(w, t2));
    int sum = 20 * u_caches + self; // a float after the proxies and their 3 running sums
    float side_p = sqrt(max(square_p, 0.0)), nearer = d - radius;
    float blocked = u_begin > 0 ? proxies[sum / 4][sum % 4] : 0.0;
    for (int base = u_begin; base < u_end; base += TILE) {
        int k = base + slot;
        tile_position[slot] = k < u_end ? caches[2 * k] : vec4(0.0);
        tile_normal[slot] = k < u_end ? caches[2 * k + 1] : vec4(0.0);
        barrier();
        for (int j = 0; j < TILE && lit_cache; j++) {
            if (base + j >= u_end || base + j == c)
                continue;
            vec3 u = tile_position[j].xyz - p;
            float r2 = dot(u, u);
            if (!(r2 > 0.0) || r2 >= nearer * nearer)
                continue;
            float r = sqrt(r2);
            vec3 wk = u / r;
            float cos_k = dot(n, wk);
            if (!(cos_k > 0.0))
                continue;
            float solid = min(2.0 * PI, tile_position[j].w * abs(dot(tile_normal[j].xyz, wk)) / r2);
            blocked += overlap(cp, side_p, vec2(dot(wk, t1), dot(wk, t2)), sqrt(solid * cos_k));
        }
        barrier();
    }
    if (!lit_cache)
        return;
    if (u_last == 0) {
        proxies[sum / 4][sum % 4] = blocked;
        return;
    }
    float visibility = max(0.0, 1.0 - blocked / square_p);
    vec4 e = proxies[2 * c + 1];
    proxies[2 * c + 1] = vec4(e.rgb * visibility, visibility);
#ifdef GLOSSY
    int g = GLOSSY_PART * u_caches + 2 * c + 1;
    proxies[g] = vec4(proxies[g].rgb * visibility, visibility);
#endif
}
