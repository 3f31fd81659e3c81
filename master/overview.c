#include "overview.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "image/font.h"
#include "image/image.h"

const uint8_t overview_label_text[3] = {255, 255, 255}, overview_label_back[3] = {0, 0, 0};
static const uint8_t canvas_grey = 24;

int overview_size(const cluster_config *cfg, int *width, int *height, char *err, size_t errlen)
{
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
    *width = cw;
    *height = ch;
    return 0;
}

void overview_label_place(int x0, int y0, int w, int h, int *x, int *y, int *scale)
{
    *scale = w >= 128 && h >= 128 ? 2 : 1;
    *x = x0 + 3 * *scale;
    *y = y0 + 3 * *scale;
}

int overview_draw(const cluster_config *cfg, const char *dir, int missing_ok, uint8_t *canvas, int cw, int ch,
                  char *err, size_t errlen)
{
    memset(canvas, canvas_grey, (size_t)cw * ch * 3);
    int drawn = 0;
    for (int n = 0; n < cfg->node_count; n++)
        for (int s = 0; s < cfg->nodes[n].screen_count; s++) {
            const cluster_node_screen *ns = &cfg->nodes[n].screens[s];
            const cluster_screen *sc = &cfg->screens[ns->screen];
            int x0 = sc->overview[0], y0 = sc->overview[1];
            if (x0 < 0)
                continue;
            cluster_eyes e = cfg->nodes[n].eyes;
            const char *eye = e == CLUSTER_EYES_STEREO || e == CLUSTER_EYES_LEFT ? "left" :
                              e == CLUSTER_EYES_RIGHT ? "right" : "mono";
            char path[2048];
            snprintf(path, sizeof path, "%s/%s-%s.png", dir, sc->name, eye);
            int w = ns->width, h = ns->height;
            uint8_t *img = NULL;
            if (missing_ok && access(path, R_OK) != 0) {
                for (int y = y0; y < y0 + h && y < ch; y++) /* its place stays black */
                    memset(canvas + ((size_t)y * cw + x0) * 3, 0, (size_t)(x0 + w <= cw ? w : cw - x0) * 3);
            } else if (image_read_png(path, &w, &h, &img, err, errlen) != 0) {
                char why[512];
                snprintf(why, sizeof why, "%s", err);
                snprintf(err, errlen, "overview: %s (did every node write its images?)", why);
                return -1;
            } else {
                for (int y = 0; y < h && y0 + y < ch; y++) {
                    int cols = w < cw - x0 ? w : cw - x0;
                    memcpy(canvas + ((size_t)(y0 + y) * cw + x0) * 3, img + (size_t)y * w * 3, (size_t)cols * 3);
                }
                free(img);
                drawn++;
            }
            /* The wall's name in its corner, readable on any picture. */
            int lx, ly, scale;
            overview_label_place(x0, y0, w, h, &lx, &ly, &scale);
            font_draw(canvas, cw, ch, lx, ly, scale, sc->name, overview_label_text, overview_label_back);
        }
    return drawn;
}

int overview_compose(const cluster_config *cfg, const char *dir, const char *out_path, char *err, size_t errlen)
{
    int cw, ch;
    if (overview_size(cfg, &cw, &ch, err, errlen) != 0)
        return -1;
    /* not xalloc: the config's screens' size: refused in err */
    uint8_t *canvas = malloc((size_t)cw * ch * 3);
    if (!canvas) {
        snprintf(err, errlen, "overview: out of memory for %d x %d pixels", cw, ch);
        return -1;
    }
    int rc = overview_draw(cfg, dir, 0, canvas, cw, ch, err, errlen) < 0 ? -1 : 0;
    if (rc == 0)
        rc = image_write_png(out_path, cw, ch, canvas, err, errlen);
    free(canvas);
    return rc;
}
