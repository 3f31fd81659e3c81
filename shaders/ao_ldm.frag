// Ambient occlusion against the layered depth maps (node/renderer_ao.h): from the pixel's
// surface point, one ray per map along the map's direction on the normal's side (a map
// is traced both ways, so each of the n maps gives exactly one direction of the
// hemisphere), its visibility weighted by the cosine. The sum is divided by the cosines'
// sum, not by n/2: the equal-area directions' own quadrature error (1.25% at 64 maps,
// tests/unit/test_ldm.c) then leaves an open surface at exactly 1.
in vec2 v_uv;

uniform sampler2D u_position;
uniform sampler2D u_normal;

layout(location = 0) out vec4 out_ao;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 pw = texelFetch(u_position, px, 0);
    if (pw.w == 0.0) {
        out_ao = vec4(1.0);
        return;
    }
    vec3 p = pw.xyz;
    vec3 n = normalize(texelFetch(u_normal, px, 0).xyz);
    float seen = 0.0, total = 0.0;
    for (int m = 0; m < u_ldm_count; m++) {
        float c = dot(n, ldm_direction(m));
        if (c == 0.0)
            continue;
        float d = ldm_trace_from(m, sign(c), p, n);
        seen += ao_visibility(d) * abs(c);
        total += abs(c);
    }
    out_ao = vec4(vec3(total > 0.0 ? seen / total : 1.0), 1.0);
}
