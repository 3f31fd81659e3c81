// The G-buffer's four outputs for an application's points and lines (gbuffer.frag's layout):
// lit, shadowed and tone-mapped like the scene by the passes after it.
in vec3 v_position;
in vec3 v_normal;
in vec3 v_color;

uniform vec4 u_eye;
uniform float u_roughness;

layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_albedo;
layout(location = 3) out vec4 out_emissive;

void main()
{
    vec3 n = normalize(v_normal);
    if (dot(n, u_eye.xyz - v_position * u_eye.w) < 0.0)
        n = -n;
    out_position = vec4(v_position, 1.0);
    out_normal = vec4(n, u_roughness);
    out_albedo = vec4(clamp(v_color, 0.0, 1.0), 1.0);
    out_emissive = vec4(0.0, 0.0, 0.0, 1.0);
}
