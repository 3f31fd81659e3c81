/* preview: the live window of the unfolded walls (preview.h). */
#include "preview.h"

#include <stdio.h>
#include <stdlib.h>
#include <GLFW/glfw3.h>

#include "base/clock.h"
#include "base/xalloc.h"
#include "overview.h"
#include "pixel_window.h"

struct preview {
    const cluster_config *cfg;
    const char *dir;
    pixel_window *pw;
    uint8_t *canvas;
    int width, height;
    double last_ms;
    int closed, shown;
};

preview *preview_open(const cluster_config *cfg, const char *dir, char *err, size_t errlen)
{
    int w, h;
    char why[400];
    if (overview_size(cfg, &w, &h, why, sizeof why) != 0) {
        snprintf(err, errlen, "preview: %s", why);
        return NULL;
    }
    int side = w > h ? w : h;
    float fit = side > PREVIEW_MAX_SIDE ? (float)PREVIEW_MAX_SIDE / side : 1.0f;
    char title[300];
    snprintf(title, sizeof title, "cavelight preview: %s", cfg->path);
    pixel_window *pw = pixel_window_open(&(pixel_window_desc){.title = title, .width = (int)(w * fit),
                                                              .height = (int)(h * fit), .resizable = 1},
                                         why, sizeof why);
    if (!pw) {
        snprintf(err, errlen, "preview: %s; going on without it", why);
        return NULL;
    }
    preview *p = xcalloc(1, sizeof *p);
    p->cfg = cfg;
    p->dir = dir;
    p->pw = pw;
    p->width = w;
    p->height = h;
    p->canvas = xmalloc((size_t)w * h * 3);
    p->last_ms = -1e9;
    return p;
}

int preview_update(preview *p, int force)
{
    if (p->closed)
        return 0;
    glfwPollEvents();
    if (pixel_window_should_close(p->pw)) {
        p->closed = 1;
        return 1;
    }
    double now = clock_now_ms();
    if (!force && now - p->last_ms < 1000.0 / PREVIEW_HZ)
        return 0;
    p->last_ms = now;
    char err[512];
    int n = overview_draw(p->cfg, p->dir, 1, p->canvas, p->width, p->height, err, sizeof err);
    if (n < 0) /* an unreadable image (not a missing one): the next update tries again */
        return 0;
    p->shown = n;
    pixel_window_show(p->pw, p->canvas, p->width, p->height);
    return 0;
}

int preview_screens_shown(const preview *p)
{
    return p->shown;
}

void *preview_window(preview *p)
{
    return pixel_window_glfw(p->pw);
}

void preview_close(preview *p)
{
    if (!p)
        return;
    pixel_window_close(p->pw);
    free(p->canvas);
    free(p);
}
