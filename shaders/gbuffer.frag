// Camera G-buffer: world position, normal facing the viewer, albedo, emitted radiance.
in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;

uniform vec4 u_base_color;
uniform int u_has_texture;
uniform sampler2D u_base_texture;   // sRGB texture: sampled values are linear
uniform vec3 u_emissive;
uniform float u_roughness;
uniform vec4 u_eye;                 // the eye (w 1), or the direction towards it (w 0: orthographic)

layout(location = 0) out vec4 out_position;  // xyz world, w = 1 where geometry is
layout(location = 1) out vec4 out_normal;    // xyz unit normal, w = roughness
layout(location = 2) out vec4 out_albedo;
layout(location = 3) out vec4 out_emissive;

void main()
{
    vec3 n = normalize(v_normal);
    // Two-sided surfaces: shade the side the eye sees.
    if (dot(n, u_eye.xyz - v_position * u_eye.w) < 0.0)
        n = -n;
    vec4 albedo = u_base_color;
    if (u_has_texture != 0)
        albedo *= texture(u_base_texture, v_uv);
    out_position = vec4(v_position, 1.0);
    out_normal = vec4(n, u_roughness);
    out_albedo = vec4(albedo.rgb, 1.0);
    out_emissive = vec4(u_emissive, 1.0);
}
