// The vpl method's shading snippet (gi_method.h), after shaders/shade.frag and
// vpl_gather.glsl: every VPL the pixel's cluster lists, or, interleaved, the gathered and
// blurred irradiance of the pixel (vpl_interleave.h).
uniform int u_vpl_interleaved;       // 1: the irradiance is u_vpl_irradiance's
uniform sampler2D u_vpl_irradiance;

vec3 gi_irradiance(vec3 p, vec3 n)
{
    if (u_vpl_count <= 0)
        return vec3(0.0);
    if (u_vpl_interleaved != 0)
        return texelFetch(u_vpl_irradiance, ivec2(gl_FragCoord.xy), 0).rgb;
    return vpl_irradiance(p, n, 0, 1);
}
