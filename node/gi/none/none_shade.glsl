// The none method's shading snippet (gi_method.h): a constant indirect irradiance (W/m^2;
// none-irradiance, 0 by default: direct light only).
uniform vec3 u_none_irradiance;

vec3 gi_irradiance(vec3 p, vec3 n)
{
    return u_none_irradiance;
}
