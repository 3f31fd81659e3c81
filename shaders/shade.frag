// Deferred shading (paper 3.3.3 and 3.3.4): direct light of every light with normalized
// Blinn-Phong (spots: the D3D cone; spots and point lights: inverse-square falloff;
// directional lights: parallel) and 3x3 PCF against the light's RSM;
// indirect light from the active GI method (gi_irradiance(), and gi_glossy() where the
// method has it); emitted radiance of surface lights; the ambient light times its
// occlusion (node/renderer_ao.h), counted as direct light (it reaches the surface from its
// source without a reflection). HDR out, linear.
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
uniform sampler2D u_ao;              // the ambient occlusion of this eye (renderer_ao.h)
uniform int u_ao_on;                 // 0: none computed, AO is 1
uniform float u_ambient;             // the ambient light's radiance, W/(m^2 sr)

// The active GI method's irradiance at p (normal n), W/m^2 before the albedo: defined by
// the method's shading snippet, compiled after this file (node/gi/gi_method.h).
vec3 gi_irradiance(vec3 p, vec3 n);
#ifdef GI_GLOSSY
// a method with gi_method.glossy also defines the indirect light that p reflects towards
// the eye (unit v), as radiance: its specular term (node/gi/gi_method.h)
vec3 gi_glossy(vec3 p, vec3 n, vec3 v);
#endif

layout(location = 0) out vec4 out_final;
layout(location = 1) out vec4 out_direct;
layout(location = 2) out vec4 out_indirect;

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
    float m = specular_exponent(nr.w);

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
        vec3 brdf = albedo / PI + specular_brdf(m, n, h);
        direct += brdf * irradiance;
    }

    if (u_ambient > 0.0) { // irradiance pi L AO, times albedo / pi
        float ao = u_ao_on != 0 ? texelFetch(u_ao, ivec2(gl_FragCoord.xy), 0).r : 1.0;
        direct += albedo * u_ambient * ao;
    }
    vec3 indirect = albedo / PI * gi_irradiance(p, n);
#ifdef GI_GLOSSY
    indirect += gi_glossy(p, n, v);
#endif
    direct *= u_exposure;
    indirect *= u_exposure;
    out_direct = vec4(direct, 1.0);
    out_indirect = vec4(indirect, 1.0);
    out_final = vec4(direct + indirect, 1.0);
}
