/* fpmode: one fixed floating-point mode for the LPV's arithmetic.
 *
 * Results of the same operations differ when one thread flushes denormals to zero and
 * another does not, and GL drivers (Mesa's llvmpipe among them) change that mode on the
 * threads they run on. Every piece of LPV work therefore runs inside
 * fpmode_enter()/fpmode_leave(), which sets flush-to-zero and denormals-are-zero (also
 * sparing the slow denormal path) and puts the caller's mode back afterwards. Without
 * SSE the mode is left alone. */
#ifndef CAVELIGHT_FPMODE_H
#define CAVELIGHT_FPMODE_H

typedef struct fpmode {
    unsigned saved;
} fpmode;

fpmode fpmode_enter(void);
void fpmode_leave(fpmode previous);

#endif
