#include "overview.h"

#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image/font.h"
#include "image/image.h"

static uint8_t *read_png(const char *path, int *w, int *h, char *err, size_t errlen)
{
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&img, path)) {
        snprintf(err, errlen, "overview: cannot read %s (%s): did every node write its images?", path, img.message);
        return NULL;
    }
    img.format = PNG_FORMAT_RGB;
    uint8_t *rgb = malloc(PNG_IMAGE_SIZE(img));
    if (!rgb || !png_image_finish_read(&img, NULL, rgb, 0, NULL)) {
        snprintf(err, errlen, "overview: cannot decode %s", path);
        png_image_free(&img);
        free(rgb);
        return NULL;
    }
    *w = (int)img.width;
    *h = (int)img.height;
    return rgb;
}

int overview_compose(const cluster_config *cfg, const char *dir, const char *out_path, char *err, size_t errlen)
{
    /* Canvas size from the configured resolutions. */
    int cw = 0, ch = 0;
    for (int n = 0; n < cfg->node_count; n++)
        for (int s = 0; s < cfg->nodes[n].screen_count; s++) {
            const cluster_node_screen *ns = &cfg->nodes[n].screens[s];
            const cluster_screen *sc = &cfg->screens[ns->screen];
            if (sc->overview[0] < 0)
                continue;
            if (sc->overview[0] + ns->width > cw)
                cw = sc->overview[0] + ns->width;
            if (sc->overview[1] + ns->height > ch)
                ch = sc->overview[1] + ns->height;
        }
    if (cw == 0) {
        snprintf(err, errlen, "overview: no screen in %s has an \"overview\" offset", cfg->path);
        return -1;
    }
    uint8_t *canvas = malloc((size_t)cw * ch * 3);
    if (!canvas) {
        snprintf(err, errlen, "overview: out of memory");
        return -1;
    }
    memset(canvas, 24, (size_t)cw * ch * 3);
    int rc = 0;
    for (int n = 0; n < cfg->node_count && rc == 0; n++)
        for (int s = 0; s < cfg->nodes[n].screen_count && rc == 0; s++) {
            const cluster_node_screen *ns = &cfg->nodes[n].screens[s];
            const cluster_screen *sc = &cfg->screens[ns->screen];
            if (sc->overview[0] < 0)
                continue;
            cluster_eyes e = cfg->nodes[n].eyes;
            const char *eye = e == CLUSTER_EYES_STEREO || e == CLUSTER_EYES_LEFT ? "left" :
                              e == CLUSTER_EYES_RIGHT ? "right" : "mono";
            char path[2048];
            snprintf(path, sizeof path, "%s/%s-%s.png", dir, sc->name, eye);
            int w, h;
            uint8_t *img = read_png(path, &w, &h, err, errlen);
            if (!img) {
                rc = -1;
                break;
            }
            for (int y = 0; y < h && sc->overview[1] + y < ch; y++) {
                int x0 = sc->overview[0], cols = w < cw - x0 ? w : cw - x0;
                memcpy(canvas + ((size_t)(sc->overview[1] + y) * cw + x0) * 3, img + (size_t)y * w * 3, (size_t)cols * 3);
            }
            free(img);
            /* The wall's name in its corner, readable on any picture. */
            static const uint8_t text[3] = {255, 255, 255}, back[3] = {0, 0, 0};
            int scale = h >= 256 && w >= 128 ? 2 : 1;
            font_draw(canvas, cw, ch, sc->overview[0] + 3 * scale, sc->overview[1] + 3 * scale, scale, sc->name,
                      text, back);
        }
    if (rc == 0)
        rc = image_write_png(out_path, cw, ch, canvas, err, errlen);
    free(canvas);
    return rc;
}
