// Ambient occlusion's visibility function, ao_visibility() of common/frame/ao.h: a surface
// at distance d (< 0: none) hides the ambient light fully when nearer than u_ao_distance
// (occlusion), or by 1 - d / u_ao_distance (obscurance); u_ao_distance 0: at any distance.
uniform float u_ao_distance;
uniform int u_ao_falloff;        // 0 occlusion, 1 obscurance (frame_ao_falloff)

float ao_visibility(float d)
{
    if (d < 0.0)
        return 1.0;
    if (u_ao_distance <= 0.0)
        return 0.0;
    if (d >= u_ao_distance)
        return 1.0;
    return u_ao_falloff == 1 ? d / u_ao_distance : 0.0;
}
