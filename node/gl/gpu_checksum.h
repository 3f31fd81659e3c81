/* gpu_checksum: a GI method's result hashed on the GPU into two words (READY's checksum,
 * docs/cluster.md) and read back through a persistently mapped buffer after a fence, one
 * frame late, so the frame never waits for its own result:
 *
 *   late = gpu_checksum_frame(c)    a frame begins: the value of the last frame submitted
 *                                   before it (waits only when the GPU is still on it;
 *                                   frames that submit nothing keep it), and its sums
 *                                   start at 0
 *   gpu_checksum_add(c, buf, o, n, w, s)  n records of shader storage buffer buf from
 *                                   word o on, s words apart: the first w words of each
 *   gpu_checksum_submit(c)          v's parts are all in: its fence
 *
 * The value is order free over the words' parallel sum (shaders/checksum.comp), so equal
 * buffers give equal bits on every node; 0 for a frame with no parts. A NULL c is
 * accepted and adds nothing. */
#ifndef CAVELIGHT_GPU_CHECKSUM_H
#define CAVELIGHT_GPU_CHECKSUM_H

#include <stddef.h>
#include <stdint.h>

#include "gl_functions.h"

typedef struct gpu_checksum gpu_checksum;

/* NULL with one line in err (its shader). */
gpu_checksum *gpu_checksum_create(const gl_functions *gl, char *err, size_t errlen);
void gpu_checksum_destroy(gpu_checksum *c);
uint64_t gpu_checksum_frame(gpu_checksum *c);
void gpu_checksum_add(gpu_checksum *c, GLuint buffer, size_t offset_words, size_t records,
                      int width, int stride);
void gpu_checksum_submit(gpu_checksum *c);

#endif
