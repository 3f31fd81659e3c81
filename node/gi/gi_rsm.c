#include "gi/gi_rsm.h"

#include <stdlib.h>

int gi_rsm_read_layer(gi_rsm_reader *r, const gl_functions *gl, const gi_rsm *rsm, int layer,
                      const float **position, const float **normal, const float **flux)
{
    size_t texels = (size_t)rsm->size * rsm->size;
    if (texels > r->texels) {
        gi_rsm_reader_free(r);
        for (int b = 0; b < 3; b++) /* not xalloc: the RSM size (a setting): -1 */
            if (!(r->read[b] = malloc(texels * 4 * sizeof(float)))) {
                gi_rsm_reader_free(r);
                return -1;
            }
        r->texels = texels;
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, rsm->fbo[layer]);
    gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
    for (int b = 0; b < 3; b++) {
        gl->ReadBuffer(GL_COLOR_ATTACHMENT0 + b);
        gl->ReadPixels(0, 0, rsm->size, rsm->size, GL_RGBA, GL_FLOAT, r->read[b]);
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    *position = r->read[0];
    *normal = r->read[1];
    *flux = r->read[2];
    return 0;
}

void gi_rsm_reader_free(gi_rsm_reader *r)
{
    for (int b = 0; b < 3; b++)
        free(r->read[b]);
    *r = (gi_rsm_reader){0};
}
