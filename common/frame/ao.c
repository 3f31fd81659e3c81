/* ao: see ao.h. */
#include "frame/ao.h"

#include "frame/frame_params.h"

float ao_visibility(float d, float max_d, frame_ao_falloff f)
{
    if (d < 0)
        return 1.0f;
    if (max_d <= 0)
        return 0.0f;
    if (d >= max_d)
        return 1.0f;
    return f == FRAME_AO_OBSCURANCE ? d / max_d : 0.0f;
}

const char *ao_ambient_check(const frame_params *p)
{
    if (p->ao == FRAME_AO_OFF || p->ambient > 0)
        return NULL;
    return "--ao occludes the ambient term, which is 0: no pixel would change (give "
           "--ambient L, e.g. 0.5, or --ao off)";
}

