// The ldm method's shading snippet (gi_method.h): the irradiance its split photons
// splatted onto this eye's pixels (gi_ldm.h), or none.
uniform int u_ldm_on;
uniform sampler2D u_ldm_irradiance;

vec3 gi_irradiance(vec3 p, vec3 n)
{
    return u_ldm_on != 0 ? texelFetch(u_ldm_irradiance, ivec2(gl_FragCoord.xy), 0).rgb : vec3(0.0);
}
