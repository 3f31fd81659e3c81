#include "base/fpmode.h"

#if defined(__SSE__)
#include <xmmintrin.h>

enum { MXCSR_FLUSH_TO_ZERO = 0x8000, MXCSR_DENORMALS_ARE_ZERO = 0x0040 };

fpmode fpmode_enter(void)
{
    fpmode m = {_mm_getcsr()};
    _mm_setcsr(m.saved | MXCSR_FLUSH_TO_ZERO | MXCSR_DENORMALS_ARE_ZERO);
    return m;
}

void fpmode_leave(fpmode previous)
{
    _mm_setcsr(previous.saved);
}
#else
fpmode fpmode_enter(void)
{
    fpmode m = {0};
    return m;
}

void fpmode_leave(fpmode previous)
{
    (void)previous;
}
#endif
