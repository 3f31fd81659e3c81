// HUD: drawn into the final (display-encoded) image after tone mapping, so its colours
// are not compressed by L/(1+L): linear colour, a head light for shape, then the same
// encoding gamma as the final pass. White stays white, grey 0.5 stays clearly darker.
in vec3 v_position;
in vec3 v_normal;

uniform vec3 u_color;
uniform vec3 u_eye;
uniform float u_encoding_gamma;

layout(location = 0) out vec4 out_color;

void main()
{
    vec3 n = normalize(v_normal);
    float facing = abs(dot(n, normalize(u_eye - v_position)));
    vec3 c = clamp(u_color, 0.0, 1.0) * (0.55 + 0.45 * facing);
    out_color = vec4(pow(c, vec3(u_encoding_gamma)), 1.0);
}
