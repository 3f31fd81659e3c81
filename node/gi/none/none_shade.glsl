// The none method's shading snippet (gi_method.h): no indirect light.
vec3 gi_irradiance(vec3 p, vec3 n)
{
    return vec3(0.0);
}
