// Interpolation (cache_interpolate()): every cache the pixel's grid cell lists that reaches
// it and is not hidden (normal.w 1, caches_exact.h), weighted by cache_weight(), each proxy
// light's irradiance at the pixel (cache_proxy_at()), over the G-buffer into the eye's
// irradiance texture. With GLOSSY defined, also the glossy radiance towards u_eye
// (cache_interpolate_glossy()) into a second texture.
layout(location = 0) out vec4 out_irradiance;
#ifdef GLOSSY
layout(location = 1) out vec4 out_glossy;
uniform vec4 u_eye;             // the eye (w 1), or the direction towards it (w 0)
#endif

uniform sampler2D u_position;
uniform sampler2D u_normal;

layout(std430, binding = 0) readonly buffer Caches { vec4 caches[]; };
layout(std430, binding = 1) readonly buffer Proxies { vec4 proxies[]; };
layout(std430, binding = 7) readonly buffer Grid { uint grid[]; }; // first[cells + 1], index

uniform vec3 u_grid_origin;
uniform float u_grid_cell;
uniform ivec3 u_grid_dims;
uniform int u_grid_cells;
uniform int u_caches;
uniform float u_reach;
uniform float u_plane_weight;   // CACHE_PLANE_WEIGHT
uniform float u_min_cos;        // CACHE_PROXY_MIN_COS

// cache_proxy_at()'s ratio: proxy (position + radius) of the cache at cp (normal cn), at x
// (normal n).
float proxy_ratio(vec4 proxy, vec3 cp, vec3 cn, vec3 x, vec3 n)
{
    vec3 lc = proxy.xyz - cp, lx = proxy.xyz - x;
    float dc2 = dot(lc, lc), dx2 = dot(lx, lx), r2 = proxy.w * proxy.w;
    float cos_c = dc2 > 0.0 ? dot(cn, lc) / sqrt(dc2) : 1.0;
    float cos_x = dx2 > 0.0 ? dot(n, lx) / sqrt(dx2) : 1.0;
    float g = cos_x > 0.0 ? cos_x / max(cos_c, u_min_cos) * (dc2 + r2) / (dx2 + r2) : 0.0;
    if (!(dx2 + r2 > 0.0))
        g = 1.0;
    return g;
}

// The unit direction from a to b, or fallback where they meet.
vec3 towards(vec3 a, vec3 b, vec3 fallback)
{
    vec3 d = b - a;
    return dot(d, d) > 0.0 ? normalize(d) : fallback;
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 pw = texelFetch(u_position, px, 0);
#ifdef GLOSSY
    out_glossy = vec4(0.0);
#endif
    if (pw.w == 0.0) {
        out_irradiance = vec4(0.0);
        return;
    }
    vec4 nr = texelFetch(u_normal, px, 0);
    vec3 x = pw.xyz, n = normalize(nr.xyz);
    ivec3 k = clamp(ivec3(floor((x - u_grid_origin) / u_grid_cell)), ivec3(0), u_grid_dims - 1);
    int cell = (k.z * u_grid_dims.y + k.y) * u_grid_dims.x + k.x;
    vec3 sum = vec3(0.0);
    float weights = 0.0;
#ifdef GLOSSY
    vec3 gsum = vec3(0.0), gpos = vec3(0.0);
    float gweights = 0.0;
    int part = GLOSSY_PART * u_caches;
#endif
    for (uint i = grid[cell]; i < grid[cell + 1]; i++) {
        int c = int(grid[u_grid_cells + 1 + int(i)]);
        vec4 cn4 = caches[2 * c + 1];
        if (cn4.w > 0.0)
            continue;
        vec3 cp = caches[2 * c].xyz, cn = cn4.xyz;
        vec3 d = x - cp;
        float off = dot(cn, d), d2 = dot(d, d) + u_plane_weight * off * off;
        float facing = dot(n, cn);
        if (!(d2 < u_reach * u_reach) || !(facing > 0.0))
            continue;
        float falloff = 1.0 - sqrt(d2) / u_reach;
        float w = falloff * sqrt(facing);
        sum += w * proxies[2 * c + 1].rgb * proxy_ratio(proxies[2 * c], cp, cn, x, n);
        weights += w;
#ifdef GLOSSY
        // equation 8: the reflections of the incident direction (from the proxy) at x and c
        vec4 gp = proxies[part + 2 * c];
        vec3 rx = reflect(towards(gp.xyz, x, n), n);
        vec3 rc = reflect(towards(gp.xyz, cp, cn), cn);
        float r = dot(rx, rc);
        if (!(r > 0.0))
            continue;
        float wg = falloff * sqrt(r);
        gsum += wg * proxies[part + 2 * c + 1].rgb * proxy_ratio(gp, cp, cn, x, n);
        gpos += wg * gp.xyz;
        gweights += wg;
#endif
    }
    out_irradiance = vec4(weights > 0.0 ? sum / weights : vec3(0.0), 1.0);
#ifdef GLOSSY
    if (gweights > 0.0) {
        vec3 v = normalize(u_eye.xyz - x * u_eye.w), l = towards(x, gpos / gweights, n);
        out_glossy = vec4(specular_between(specular_exponent(nr.w), n, v, l) * gsum / gweights,
                          1.0);
    }
#endif
}
