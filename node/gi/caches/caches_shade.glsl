// The caches method's shading snippet (gi_method.h), after shaders/shade.frag: the pixel's
// irradiance and, with caches-glossy on, its glossy radiance, interpolated from the light
// caches before the shading pass (caches_interpolate.frag).
uniform sampler2D u_caches_irradiance;
uniform sampler2D u_caches_glossy;
uniform int u_caches_glossy_on;

vec3 gi_irradiance(vec3 p, vec3 n)
{
    return texelFetch(u_caches_irradiance, ivec2(gl_FragCoord.xy), 0).rgb;
}

vec3 gi_glossy(vec3 p, vec3 n, vec3 v)
{
    return u_caches_glossy_on != 0 ? texelFetch(u_caches_glossy, ivec2(gl_FragCoord.xy), 0).rgb
                                   : vec3(0.0);
}
