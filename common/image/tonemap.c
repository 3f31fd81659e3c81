#include "image/tonemap.h"

#include <math.h>

void tonemap_rgb8(const float *linear, size_t pixels, float encoding_gamma, uint8_t *rgb)
{
    for (size_t i = 0; i < pixels * 3; i++) {
        double l = linear[i] > 0 ? linear[i] : 0;
        double v = pow(l / (1.0 + l), encoding_gamma);
        rgb[i] = (uint8_t)lround(fmin(fmax(v, 0.0), 1.0) * 255.0);
    }
}
