// The interleaved gather's first pass (vpl_interleave.h), after vpl_gather.glsl.
uniform sampler2D u_position;        // the G-buffer's
uniform sampler2D u_normal;
uniform int u_vpl_block;             // k of the k x k blocks

layout(location = 0) out vec4 out_final;

// Fragment x of the de-interleaved image is pixel (x mod sub) k + s of the G-buffer,
// s = x / sub its block position, which gathers subset s.x + k s.y of the VPLs, scaled by
// N / its size.
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
