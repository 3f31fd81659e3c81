// Deferred shading (paper 3.3.3 and 3.3.4): direct light of every spot with normalized
// Blinn-Phong, the D3D cone, inverse-square falloff and 3x3 PCF against the RSM depth;
// indirect light from the LPV; emitted radiance of surface lights. HDR out, linear.
in vec2 v_uv;

uniform sampler2D u_position;
uniform sampler2D u_normal;
uniform sampler2D u_albedo;
uniform sampler2D u_emissive;
uniform sampler2DArrayShadow u_shadow;

uniform int u_light_count;
uniform vec3 u_light_position[MAX_LIGHTS];
uniform vec3 u_light_direction[MAX_LIGHTS];
uniform vec3 u_light_radiance[MAX_LIGHTS];
uniform float u_cos_outer[MAX_LIGHTS];
uniform float u_cos_inner[MAX_LIGHTS];
uniform mat4 u_light_view_projection[MAX_LIGHTS];
uniform float u_shadow_texel;
uniform float u_shadow_offset;       // normal offset, metres (scales with the scene)
uniform float u_min_light_distance;  // falloff bound near a light, metres (ditto)
uniform float u_absorption;
uniform vec3 u_eye;
uniform float u_exposure;

uniform int u_lpv_enabled;
uniform sampler3D u_lpv_r;
uniform sampler3D u_lpv_g;
uniform sampler3D u_lpv_b;
uniform vec3 u_lpv_origin;
uniform float u_lpv_cell;
uniform vec3 u_lpv_size;             // cells per axis
uniform float u_indirect_scale;      // light lifetime in steps (renderer.h)

layout(location = 0) out vec4 out_final;
layout(location = 1) out vec4 out_direct;
layout(location = 2) out vec4 out_indirect;

float shadow(int i, vec3 p, vec3 n)
{
    // Normal offset plus a small constant bias against self-shadowing (paper: ~5e-4); the
    // RSM's near plane scales with the scene, so the bias does too.
    vec4 q = u_light_view_projection[i] * vec4(p + n * u_shadow_offset, 1.0);
    vec3 s = q.xyz / q.w * 0.5 + 0.5;
    if (q.w <= 0.0 || any(lessThan(s.xy, vec2(0.0))) || any(greaterThan(s.xy, vec2(1.0))))
        return 0.0;
    float sum = 0.0;
    for (int y = -1; y <= 1; y++)
        for (int x = -1; x <= 1; x++)
            sum += texture(u_shadow, vec4(s.xy + vec2(x, y) * u_shadow_texel, float(i),
                                          s.z - 5e-4));
    return sum / 9.0;
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
    vec3 v = normalize(u_eye - p);
    float alpha = nr.w * nr.w;
    float m = 2.0 / max(alpha * alpha, 1e-3) - 2.0;    // Blinn-Phong exponent from roughness
    const float spec = 0.04;                          // dielectric reflectance

    vec3 direct = texture(u_emissive, v_uv).rgb;
    for (int i = 0; i < u_light_count; i++) {
        vec3 to_light = u_light_position[i] - p;
        float r2 = dot(to_light, to_light);
        float r = sqrt(r2);
        vec3 l = to_light / r;
        float cos_i = dot(n, l);
        if (cos_i <= 0.0)
            continue;
        float spot = spot_factor(-l, u_light_direction[i], u_cos_outer[i], u_cos_inner[i]);
        if (spot <= 0.0)
            continue;
        // Irradiance E = I cos / r^2, bounded near the light (10 cm in the default room).
        vec3 irradiance = u_light_radiance[i] * spot * cos_i /
                          max(r2, u_min_light_distance * u_min_light_distance) *
                          transmittance(u_absorption, r) * shadow(i, p, n);
        vec3 h = normalize(l + v);
        vec3 brdf = albedo / PI + (m + 8.0) / (8.0 * PI) * spec * pow(max(dot(n, h), 0.0), m);
        direct += brdf * irradiance;
    }

    vec3 indirect = vec3(0.0);
    if (u_lpv_enabled != 0) {
        // Algorithm 3: half a cell along the normal, trilinear SH, <SH_cos(-n)|L>, divided
        // by the cell area: the cell's intensity over its cross-section is radiance.
        vec3 lc = (p + n * (0.5 * u_lpv_cell) - u_lpv_origin) / u_lpv_cell;
        vec3 uvw = lc / u_lpv_size;
        vec4 lobe = sh_cosine_lobe(-n);
        vec3 irradiance = vec3(dot(lobe, texture(u_lpv_r, uvw)),
                               dot(lobe, texture(u_lpv_g, uvw)),
                               dot(lobe, texture(u_lpv_b, uvw)));
        irradiance = max(irradiance, vec3(0.0)) / (u_lpv_cell * u_lpv_cell);
        indirect = albedo / PI * irradiance * u_indirect_scale;
    }
    direct *= u_exposure;
    indirect *= u_exposure;
    out_direct = vec4(direct, 1.0);
    out_indirect = vec4(indirect, 1.0);
    out_final = vec4(direct + indirect, 1.0);
}
