// Re-interleaving and geometry-aware blur of the interleaved VPL gather
// (node/vpl_interleave.h): the mean of the pixel's k x k window, in which every subset of
// the VPLs appears once, over the neighbours on the pixel's surface: weight the cosine
// between the normals, and none for a neighbour farther from the pixel's tangent plane
// than a pixel's footprint there (a depth edge: another surface). Out: irradiance.
uniform sampler2D u_position;       // the G-buffer (w 0: no geometry)
uniform sampler2D u_normal;
uniform sampler2D u_deinterleaved;  // k x k sub-images of irradiance, subset (x mod k, y mod k)
uniform int u_block;                // k
uniform vec4 u_eye;                 // the eye (w 1) or the direction towards it (w 0)
uniform float u_pixel_angle;        // a pixel's width over its distance (w 0: its width)

layout(location = 0) out vec4 out_irradiance;

void main()
{
    ivec2 size = textureSize(u_position, 0), x = ivec2(gl_FragCoord.xy);
    int k = u_block;
    ivec2 sub = (size + k - 1) / k;
    vec4 pw = texelFetch(u_position, x, 0);
    out_irradiance = vec4(0.0, 0.0, 0.0, 1.0);
    if (pw.w == 0.0)
        return;
    vec3 p = pw.xyz, n = normalize(texelFetch(u_normal, x, 0).xyz);
    float footprint = (u_eye.w != 0.0 ? distance(u_eye.xyz, p) : 1.0) * u_pixel_angle;
    vec3 sum = vec3(0.0);
    float wsum = 0.0;
    for (int j = 0; j < k; j++)
        for (int i = 0; i < k; i++) {
            ivec2 q = x + ivec2(i, j) - k / 2;
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)))
                continue;
            vec4 qw = texelFetch(u_position, q, 0);
            if (qw.w == 0.0 || abs(dot(qw.xyz - p, n)) > footprint)
                continue;
            float w = max(dot(n, normalize(texelFetch(u_normal, q, 0).xyz)), 0.0);
            sum += w * texelFetch(u_deinterleaved, (q % k) * sub + q / k, 0).rgb;
            wsum += w;
        }
    if (wsum > 0.0)
        out_irradiance.rgb = sum / wsum;
}
