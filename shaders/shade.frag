// Deferred shading (paper 3.3.3 and 3.3.4): direct light of every light with normalized
// Blinn-Phong (spots: the D3D cone; spots and point lights: inverse-square falloff;
// directional lights: parallel) and 3x3 PCF against the light's RSM;
// indirect light from the LPV or from the VPLs (node/gi_vpl.h); emitted radiance of surface lights. HDR out, linear.
in vec2 v_uv;

uniform sampler2D u_position;
uniform sampler2D u_normal;
uniform sampler2D u_albedo;
uniform sampler2D u_emissive;
uniform sampler2DArrayShadow u_shadow;  // RSM depth, compared (LEQUAL)
uniform sampler2DArray u_rsm_normal;     // RSM planes: unit normal n turned to the light,
                                         // w = -n . position (0 where no geometry)

uniform int u_light_count;
uniform int u_light_type[MAX_LIGHTS];
uniform int u_light_first_view[MAX_LIGHTS];      // its RSM layer (a point light: +x face)
uniform vec3 u_light_position[MAX_LIGHTS];
uniform vec3 u_light_direction[MAX_LIGHTS];
uniform vec3 u_light_radiance[MAX_LIGHTS];       // W/sr (spot, point), W/m^2 (directional)
uniform float u_cos_outer[MAX_LIGHTS];
uniform float u_cos_inner[MAX_LIGHTS];
uniform float u_light_travel0[MAX_LIGHTS];       // directional: travel in the medium at the origin
uniform vec2 u_light_texel[MAX_LIGHTS];          // RSM texel at depth z along the view: x z + y
uniform mat4 u_light_view_projection[MAX_LIGHT_VIEWS];
uniform float u_shadow_texel;        // 1 / RSM size
uniform float u_min_light_distance;  // falloff bound near a light, metres (scales with the scene)
uniform float u_absorption;
uniform vec4 u_eye;                  // the eye (w 1), or the direction towards it (w 0)
uniform float u_exposure;

uniform int u_lpv_enabled;
uniform sampler3D u_lpv_r;           // texelFetch only
uniform sampler3D u_lpv_g;
uniform sampler3D u_lpv_b;
uniform vec3 u_lpv_origin;
uniform float u_lpv_cell;
uniform ivec3 u_lpv_size;            // cells per axis

uniform int u_vpl_count;             // 0: no VPL gather
uniform sampler2D u_vpls;            // VPL i: texels (0, i) position + area, (1, i) normal
                                     // + squared influence radius, (2, i) flux, W
uniform sampler2DArrayShadow u_vpl_shadow; // cube faces of every VPL as tiles: distance / far
uniform int u_vpl_face;              // texels per face side
uniform int u_vpl_tiles;             // tiles per atlas side
uniform float u_vpl_far;
uniform vec3 u_vpl_face_axis[6];     // face 2 a + (negative): axis, right, up (gi_vpl.c)
uniform vec3 u_vpl_face_right[6];
uniform vec3 u_vpl_face_up[6];
uniform int u_vpl_clustered;         // 0: every VPL; else the lists of p's cluster
uniform usampler2D u_vpl_cluster_first; // cluster c's list: [entry c, entry c + 1)
uniform usampler2D u_vpl_cluster_index; // VPL indices, ascending per cluster
uniform int u_vpl_list_row;          // entries per texel row of both
uniform vec3 u_vpl_grid_apex;        // the grid (common/gi/vpl_cluster.h): apex and axes,
uniform vec3 u_vpl_grid_right;
uniform vec3 u_vpl_grid_up;
uniform vec3 u_vpl_grid_forward;
uniform vec4 u_vpl_grid_window;      // window tangents: right min, up min, right max, up max
uniform vec2 u_vpl_grid_depth;       // near, log(far / near)
uniform ivec3 u_vpl_grid_size;       // tiles x, y, slices
uniform int u_vpl_visibility;        // 0: the exact maps above, else imperfect ones (u_ism)
uniform sampler2D u_ism;             // records (distance / far, x, y, radius; radius 0:
                                     // empty), one tile per VPL (node/vpl_ism.h)
uniform int u_ism_size;              // texels per tile side
uniform int u_ism_tiles;             // tiles per atlas side
uniform float u_ism_radius;          // world radius of the disk each point stands for
uniform int u_vpl_interleaved;       // 1: the irradiance is u_vpl_irradiance's, gathered
uniform sampler2D u_vpl_irradiance;  // interleaved and blurred (node/vpl_interleave.h)
uniform int u_vpl_block;             // VPL_DEINTERLEAVE: k of the k x k blocks

layout(location = 0) out vec4 out_final;
layout(location = 1) out vec4 out_direct;
layout(location = 2) out vec4 out_indirect;

// What one colour's SH coefficients L of a cell give a surface with normal n, per unit
// area (lpv_receive.h, the same rule): energy E and mean direction d with mean cosine q,
// read as the closest of beam (q = 1), clamped cosine (2/3), hemisphere (1/2) and isotropic
// light (0), whose irradiance on the surface is known in closed form, mixed linearly in q.
float lpv_closure(vec4 L, vec3 n)
{
    float e = SH_ENERGY * L.x;
    if (!(e > 0.0))
        return 0.0;
    vec3 f = vec3(-L.w, -L.y, L.z) * (1.0 / SH_Y1);
    float len = sqrt(dot(f, f));
    float q = min(len / e, 1.0);
    float t = len > 0.0 ? clamp(-dot(f, n) / len, -1.0, 1.0) : 0.0;
    float theta = acos(t);
    float beam = max(t, 0.0);
    float lobe = ((PI - theta) * t + sin(theta)) * (2.0 / (3.0 * PI));
    float hemi = 0.25 * (1.0 + t), iso = 0.25;
    float g;
    if (q >= 2.0 / 3.0)
        g = mix(lobe, beam, 3.0 * q - 2.0);
    else if (q >= 0.5)
        g = mix(hemi, lobe, 6.0 * q - 3.0);
    else
        g = mix(iso, hemi, 2.0 * q);
    return e * g;
}

// Irradiance from the LPV at surface point p with normal n (lpv_receive.h): the eight
// cells around p, trilinear weights, keeping only the cells whose centre lies in front of
// the surface's plane (light behind a wall must not reach its front) by less than the own
// layer (lpv_own_layer(): the surface's own light is kept out of it), then the closure.
vec3 lpv_irradiance(vec3 p, vec3 n)
{
    vec3 q = (p - u_lpv_origin) / u_lpv_cell - 0.5;
    vec3 i0 = floor(q), f = q - i0;
    vec4 lr = vec4(0.0), lg = vec4(0.0), lb = vec4(0.0);
    float wsum = 0.0;
    vec3 an = abs(n);
    float layer = (0.5 * (an.x + an.y + an.z) + 0.5 - LPV_BEHIND) * u_lpv_cell;
    for (int k = 0; k < 8; k++) {
        ivec3 o = ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
        vec3 w3 = mix(1.0 - f, f, vec3(o));
        float w = w3.x * w3.y * w3.z;
        vec3 centre = u_lpv_origin + (i0 + vec3(o) + 0.5) * u_lpv_cell;
        float ahead = dot(centre - p, n);
        if (ahead < -LPV_BEHIND * u_lpv_cell || ahead >= layer || !(w > 0.0))
            continue;
        ivec3 c = clamp(ivec3(i0) + o, ivec3(0), u_lpv_size - 1);
        lr += w * texelFetch(u_lpv_r, c, 0);
        lg += w * texelFetch(u_lpv_g, c, 0);
        lb += w * texelFetch(u_lpv_b, c, 0);
        wsum += w;
    }
    if (!(wsum > 0.0))
        return vec3(0.0);
    return vec3(lpv_closure(lr / wsum, n), lpv_closure(lg / wsum, n), lpv_closure(lb / wsum, n)) /
           (u_lpv_cell * u_lpv_cell);
}

// Shadow test against the RSM: a texel blocks p when its depth is nearer the light than
// p's and p lies behind the texel's plane (its normal faces the light). The
// plane test tells a true occluder from the other face of a concave corner, which is
// nearer the light too, and needs no depth bias: a bias lets a zero-thickness wall or lid
// closer than it to the receiver cast no shadow (docs/stability.md, leaks). p itself moves
// along its normal, which faces the eye and (where lit) the light, never through its own
// surface: in light space (depth z along the view's axis a, a texel spanning
// t = 2 z tan(fov/2) / size, a constant in a directional light's orthographic view; a
// point light's view is the cube face p lies in) a plane whose normal makes angle alpha with a changes depth
// by up to t sin(alpha) / |n . ray| per texel, and the filter below reads texels up to
// 2 sqrt(2) texels from the lookup; moving p by o along n puts it o / |n . ray| in front
// of the plane, so o = 2 sqrt(2) t sin(alpha) keeps a plane from shadowing itself, and
// 1/8 texel more covers float rounding (about 1e-3 texel). The filter is 3x3 bilinear PCF
// written out: the 4x4 texels around the lookup (four depth-compare gathers), weights
// (1-w, 1, 1, w) / 3 per axis.
float shadow(int i, vec3 p, vec3 n)
{
    vec3 a = u_light_direction[i], lp = u_light_position[i];
    int view = u_light_first_view[i];
    if (u_light_type[i] == LIGHT_POINT) { // the cube face p lies in: its largest axis
        vec3 v = p - lp, av = abs(v);
        int k = av.x >= av.y && av.x >= av.z ? 0 : (av.y >= av.z ? 1 : 2);
        view += 2 * k + (v[k] < 0.0 ? 1 : 0);
        a = vec3(0.0);
        a[k] = v[k] < 0.0 ? -1.0 : 1.0;
    }
    float texel = u_light_texel[i].x * dot(p - lp, a) + u_light_texel[i].y;
    float cos_a = dot(n, a);
    float sin_a = sqrt(max(1.0 - cos_a * cos_a, 0.0));
    vec3 q = p + n * (texel * (2.828427 * sin_a + 0.125));
    vec4 c = u_light_view_projection[view] * vec4(q, 1.0);
    vec2 s = c.xy / c.w * 0.5 + 0.5;
    if (c.w <= 0.0 || any(lessThan(s, vec2(0.0))) || any(greaterThan(s, vec2(1.0))))
        return 0.0;
    float depth = c.z / c.w * 0.5 + 0.5;
    // textureGather's texels: (i, j+1), (i+1, j+1), (i+1, j), (i, j) of the 2x2 block.
    vec2 f = s / u_shadow_texel - 0.5;
    vec2 w = fract(f);
    ivec2 t0 = ivec2(floor(f)) - 1, last = ivec2(round(1.0 / u_shadow_texel)) - 1;
    vec4 wx = vec4(1.0 - w.x, 1.0, 1.0, w.x), wy = vec4(1.0 - w.y, 1.0, 1.0, w.y);
    const ivec2 corner[4] = ivec2[4](ivec2(0, 1), ivec2(1, 1), ivec2(1, 0), ivec2(0, 0));
    float lit = 0.0;
    for (int by = 0; by < 4; by += 2)
        for (int bx = 0; bx < 4; bx += 2) {
            vec2 centre = (vec2(t0 + ivec2(bx, by)) + 1.0) * u_shadow_texel;
            vec4 farther = textureGather(u_shadow, vec3(centre, float(view)), depth);
            for (int k = 0; k < 4; k++) {
                ivec2 xy = ivec2(bx, by) + corner[k];
                vec4 plane = texelFetch(u_rsm_normal, ivec3(clamp(t0 + xy, ivec2(0), last), view), 0);
                bool blocks = farther[k] == 0.0 && dot(plane.xyz, q) + plane.w < 0.0;
                lit += blocks ? 0.0 : wx[xy.x] * wy[xy.y];
            }
        }
    return lit / 9.0;
}

// Is VPL i at y visible from p? Its distance map holds, per texel, the distance to the
// nearest surface. p moves along its normal n (which faces the VPL) as in shadow() above:
// a plane at angle beta to the ray changes distance by up to t tan(beta) per texel t =
// 2 z / face (z: depth along the face's axis), the bilinear compare reads texels up to
// sqrt(2) texels away, so o = sqrt(2) t sin(beta) + t / 8 keeps a plane from shadowing
// itself.
float vpl_visible(int i, vec3 y, vec3 p, vec3 n)
{
    vec3 d = p - y;
    vec3 a = abs(d);
    float z = max(a.x, max(a.y, a.z));
    float r = length(d);
    float cos_b = abs(dot(n, d)) / r;
    float sin_b = sqrt(max(1.0 - cos_b * cos_b, 0.0));
    float t = 2.0 * z / float(u_vpl_face);
    d += n * (t * (1.414214 * sin_b + 0.125));
    a = abs(d);
    int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    int face = 2 * axis + (d[axis] < 0.0 ? 1 : 0);
    float depth = dot(d, u_vpl_face_axis[face]);
    vec2 st = vec2(dot(d, u_vpl_face_right[face]), dot(d, u_vpl_face_up[face])) / depth;
    float size = float(u_vpl_face);
    vec2 texel = clamp((st * 0.5 + 0.5) * size, vec2(0.5), vec2(size - 0.5));
    int per_layer = u_vpl_tiles * u_vpl_tiles;
    int tile = i * 6 + face;
    int k = tile % per_layer;
    vec2 uv = (vec2(k % u_vpl_tiles, k / u_vpl_tiles) * size + texel) / (size * float(u_vpl_tiles));
    return texture(u_vpl_shadow, vec4(uv, float(tile / per_layer), length(d) / u_vpl_far));
}

// Is VPL i at y (normal m) visible from p through its imperfect shadow map? p moves along
// n as in vpl_visible(), for a texel of the paraboloid map (t = 2 r (1 + z) / size at
// distance r, cosine z to m) and for the disk of radius u_ism_radius each record spreads
// a point's depth over: o = (sqrt(2) t + radius) sin(beta) + t / 8. Bilinear weights over
// the four texels around the lookup, within the VPL's tile; an empty texel sees nothing.
float ism_visible(int i, vec3 y, vec3 m, vec3 p, vec3 n)
{
    vec3 d = p - y;
    float r = length(d);
    float size = float(u_ism_size);
    float t = 2.0 * r * (1.0 + ism_project(m, d).z) / size;
    float cos_b = abs(dot(n, d)) / r;
    float sin_b = sqrt(max(1.0 - cos_b * cos_b, 0.0));
    d += n * ((1.414214 * t + u_ism_radius) * sin_b + 0.125 * t);
    vec3 q = ism_project(m, d);
    float depth = length(d) / u_vpl_far;
    ivec2 origin = ivec2(i % u_ism_tiles, i / u_ism_tiles) * u_ism_size;
    vec2 f = clamp((q.xy * 0.5 + 0.5) * size, vec2(0.5), vec2(size - 0.5)) - 0.5;
    ivec2 t0 = ivec2(floor(f));
    vec2 w = fract(f);
    float lit = 0.0;
    for (int k = 0; k < 4; k++) {
        ivec2 o = ivec2(k & 1, k >> 1);
        vec4 record = texelFetch(u_ism, origin + min(t0 + o, ivec2(u_ism_size - 1)), 0);
        vec2 wk = mix(1.0 - w, w, vec2(o));
        lit += record.w <= 0.0 || depth <= record.x ? wk.x * wk.y : 0.0;
    }
    return lit;
}

// Irradiance at p (normal n) from VPL i: a disk of its area A seen on its axis,
// flux cos_l cos_x / (A + pi r^2) (eq. 14 of the high-res RSM paper): a point light's
// flux / pi cos_l cos_x / r^2 away from it, bounded near it; nothing beyond its influence
// radius (vpl_cluster.h).
vec3 vpl_light(int i, vec3 p, vec3 n)
{
    vec4 ya = texelFetch(u_vpls, ivec2(0, i), 0);
    vec3 d = ya.xyz - p;
    float r2 = dot(d, d);
    vec4 nl = texelFetch(u_vpls, ivec2(1, i), 0);
    if (r2 <= 0.0 || r2 > nl.w)
        return vec3(0.0);
    vec3 w = d * inversesqrt(r2);
    float cos_x = dot(n, w);
    float cos_l = -dot(nl.xyz, w);
    if (cos_x <= 0.0 || cos_l <= 0.0)
        return vec3(0.0);
    vec3 flux = texelFetch(u_vpls, ivec2(2, i), 0).rgb;
    float g = cos_l * cos_x / (ya.w + PI * r2) * transmittance(u_absorption, sqrt(r2));
    float visible = u_vpl_visibility == 0 ? vpl_visible(i, ya.xyz, p, n)
                                          : ism_visible(i, ya.xyz, nl.xyz, p, n);
    return flux * (g * visible);
}

// The cluster holding p: vpl_grid_cluster() of common/gi/vpl_cluster.c, the same rule.
int vpl_cluster(vec3 p)
{
    vec3 rel = p - u_vpl_grid_apex;
    float depth = dot(rel, u_vpl_grid_forward);
    vec2 t = vec2(dot(rel, u_vpl_grid_right), dot(rel, u_vpl_grid_up)) / depth;
    vec2 f = (t - u_vpl_grid_window.xy) / (u_vpl_grid_window.zw - u_vpl_grid_window.xy);
    float s = log(depth / u_vpl_grid_depth.x) / u_vpl_grid_depth.y;
    ivec3 c = clamp(ivec3(floor(vec3(f, s) * vec3(u_vpl_grid_size))), ivec3(0),
                    u_vpl_grid_size - 1);
    return (c.z * u_vpl_grid_size.y + c.y) * u_vpl_grid_size.x + c.x;
}

uint vpl_list_entry(usampler2D list, int k)
{
    return texelFetch(list, ivec2(k % u_vpl_list_row, k / u_vpl_list_row), 0).r;
}

// Irradiance at p from VPLs first, first + step, ... (an interleaved subset; 0, 1: all)
// among its cluster's, or among every VPL: the same terms in the same order (a cluster
// lists every VPL that can reach it, ascending).
vec3 vpl_irradiance(vec3 p, vec3 n, int first, int step)
{
    vec3 e = vec3(0.0);
    if (u_vpl_clustered == 0) {
        for (int i = first; i < u_vpl_count; i += step)
            e += vpl_light(i, p, n);
        return e;
    }
    int c = vpl_cluster(p);
    int last = int(vpl_list_entry(u_vpl_cluster_first, c + 1));
    for (int k = int(vpl_list_entry(u_vpl_cluster_first, c)); k < last; k++) {
        int i = int(vpl_list_entry(u_vpl_cluster_index, k));
        if (i % step == first)
            e += vpl_light(i, p, n);
    }
    return e;
}

#ifdef VPL_DEINTERLEAVE
// The interleaved gather's first pass (node/vpl_interleave.h): fragment x of the
// de-interleaved image is pixel (x mod sub) k + s of the G-buffer, s = x / sub its block
// position, which gathers subset s.x + k s.y of the VPLs, scaled by N / its size.
void main()
{
    int k = u_vpl_block, step = k * k;
    ivec2 size = textureSize(u_position, 0), sub = (size + k - 1) / k;
    ivec2 x = ivec2(gl_FragCoord.xy), s = x / sub, q = (x % sub) * k + s;
    int first = s.x + k * s.y, in_subset = (u_vpl_count - first + step - 1) / step;
    out_final = vec4(0.0, 0.0, 0.0, 1.0);
    if (any(greaterThanEqual(q, size)) || in_subset <= 0)
        return;
    vec4 pw = texelFetch(u_position, q, 0);
    if (pw.w == 0.0)
        return;
    vec3 n = normalize(texelFetch(u_normal, q, 0).xyz);
    out_final.rgb = vpl_irradiance(pw.xyz, n, first, step) *
                    (float(u_vpl_count) / float(in_subset));
}
#else
void main()
{
    vec4 pw = texture(u_position, v_uv);
    if (pw.w == 0.0) {
        out_final = out_direct = out_indirect = vec4(0.0, 0.0, 0.0, 1.0);
        return;
    }
    vec3 p = pw.xyz;
    vec4 nr = texture(u_normal, v_uv);
    vec3 n = normalize(nr.xyz);
    vec3 albedo = texture(u_albedo, v_uv).rgb;
    vec3 v = normalize(u_eye.xyz - p * u_eye.w);
    float alpha = nr.w * nr.w;
    float m = 2.0 / max(alpha * alpha, 1e-3) - 2.0;    // Blinn-Phong exponent from roughness
    const float spec = 0.04;                          // dielectric reflectance

    vec3 direct = texture(u_emissive, v_uv).rgb;
    for (int i = 0; i < u_light_count; i++) {
        vec3 l;
        vec3 irradiance = u_light_radiance[i];   // times what reaches p, below
        if (u_light_type[i] == LIGHT_DIRECTIONAL) {
            l = -u_light_direction[i];
            float travel = dot(p, u_light_direction[i]) + u_light_travel0[i];
            irradiance *= transmittance(u_absorption, travel);
        } else {
            vec3 to_light = u_light_position[i] - p;
            float r2 = dot(to_light, to_light);
            float r = sqrt(r2);
            l = to_light / r;
            if (u_light_type[i] == LIGHT_SPOT)
                irradiance *= spot_factor(-l, u_light_direction[i], u_cos_outer[i], u_cos_inner[i]);
            // E = I cos / r^2, bounded near the light (10 cm in the default room).
            irradiance *= transmittance(u_absorption, r) /
                          max(r2, u_min_light_distance * u_min_light_distance);
        }
        float cos_i = dot(n, l);
        if (cos_i <= 0.0 || all(equal(irradiance, vec3(0.0))))
            continue;
        irradiance *= cos_i * shadow(i, p, n);
        vec3 h = normalize(l + v);
        vec3 brdf = albedo / PI + (m + 8.0) / (8.0 * PI) * spec * pow(max(dot(n, h), 0.0), m);
        direct += brdf * irradiance;
    }

    vec3 indirect = vec3(0.0);
    if (u_lpv_enabled != 0)
        indirect = albedo / PI * lpv_irradiance(p, n);
    if (u_vpl_count > 0)
        indirect = albedo / PI * (u_vpl_interleaved != 0
                                      ? texelFetch(u_vpl_irradiance, ivec2(gl_FragCoord.xy), 0).rgb
                                      : vpl_irradiance(p, n, 0, 1));
    direct *= u_exposure;
    indirect *= u_exposure;
    out_direct = vec4(direct, 1.0);
    out_indirect = vec4(indirect, 1.0);
    out_final = vec4(direct + indirect, 1.0);
}
#endif
