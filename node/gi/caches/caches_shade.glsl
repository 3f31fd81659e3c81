// The caches method's shading snippet (gi_method.h), after shaders/shade.frag: the pixel's
// irradiance, interpolated from the light caches before the shading pass
// (caches_interpolate.frag).
uniform sampler2D u_caches_irradiance;

vec3 gi_irradiance(vec3 p, vec3 n)
{
    return texelFetch(u_caches_irradiance, ivec2(gl_FragCoord.xy), 0).rgb;
}
