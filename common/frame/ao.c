/* ao: see ao.h. */
#include "frame/ao.h"


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
