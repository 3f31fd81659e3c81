// Final pass (paper 3.3.6): the local tone operator L / (1 + L), then the encoding gamma
// end-to-end gamma / display gamma.
in vec2 v_uv;

uniform sampler2D u_hdr;
uniform float u_encoding_gamma;

layout(location = 0) out vec4 out_color;

void main()
{
    vec3 l = max(texture(u_hdr, v_uv).rgb, vec3(0.0));
    vec3 mapped = l / (1.0 + l);
    vec3 encoded = pow(mapped, vec3(u_encoding_gamma));
    // Black in 8 bits: left out (the target is cleared to black), so that the renderer's
    // sample query tells whether the view shows any light.
    if (all(lessThan(encoded, vec3(0.5 / 255.0))))
        discard;
    out_color = vec4(encoded, 1.0);
}
