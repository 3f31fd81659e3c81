/* The overview of the demo's CAVE (configs/clusters/cave5-local.json) from images as the
 * nodes write them: every screen's picture lies at its offset, every wall carries its name
 * (the label's pixels equal the font's drawing of the name at overview_label_place()), a
 * missing image is one line naming the file, and the live view (missing_ok) leaves a
 * screen without an image black and still labelled. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "image/font.h"
#include "image/image.h"
#include "overview.h"

static cluster_config cfg;

/* A colour of its own for screen s, never the label's white or black. */
static void screen_colour(int s, uint8_t c[3])
{
    c[0] = (uint8_t)(40 + 20 * s);
    c[1] = (uint8_t)(200 - 15 * s);
    c[2] = (uint8_t)(90 + 7 * s);
}

static void write_screens(const char *dir)
{
    char err[512], path[1024];
    for (int n = 0; n < cfg.node_count; n++) {
        const cluster_node_screen *ns = &cfg.nodes[n].screens[0];
        uint8_t c[3];
        screen_colour(ns->screen, c);
        uint8_t *rgb = malloc((size_t)ns->width * ns->height * 3);
        for (int i = 0; i < ns->width * ns->height; i++)
            memcpy(rgb + 3 * i, c, 3);
        snprintf(path, sizeof path, "%s/%s-left.png", dir, cfg.screens[ns->screen].name);
        if (image_write_png(path, ns->width, ns->height, rgb, err, sizeof err) != 0)
            fail_msg("%s", err);
        free(rgb);
    }
}

/* Pixels of screen s's label that show the text colour where the font draws it, and the
 * pixels the font draws. */
static void label_pixels(const uint8_t *canvas, int cw, int ch, int s, int *match, int *want)
{
    const cluster_node_screen *ns = &cfg.nodes[s].screens[0];
    const cluster_screen *sc = &cfg.screens[ns->screen];
    int x, y, scale;
    overview_label_place(sc->overview[0], sc->overview[1], ns->width, ns->height, &x, &y, &scale);
    uint8_t *ref = calloc((size_t)cw * ch, 3);
    font_draw(ref, cw, ch, x, y, scale, sc->name, overview_label_text, NULL);
    *match = *want = 0;
    for (int i = 0; i < cw * ch; i++)
        if (!memcmp(ref + 3 * i, overview_label_text, 3)) {
            (*want)++;
            *match += !memcmp(canvas + 3 * i, overview_label_text, 3);
        }
    free(ref);
}

static void test_cave5_overview(void **state)
{
    (void)state;
    char config[1024], dir[] = "/tmp/cavelight-overview-XXXXXX", err[512], out[1100];
    snprintf(config, sizeof config, "%s/configs/clusters/cave5-local.json", CAVELIGHT_SOURCE_DIR);
    assert_int_equal(cluster_config_load(config, &cfg, err, sizeof err), 0);
    assert_non_null(mkdtemp(dir));
    write_screens(dir);
    snprintf(out, sizeof out, "%s/overview.png", dir);
    if (overview_compose(&cfg, dir, out, err, sizeof err) != 0)
        fail_msg("%s", err);
    int cw, ch;
    uint8_t *canvas;
    assert_int_equal(image_read_png(out, &cw, &ch, &canvas, err, sizeof err), 0);
    /* 256 pixels a wall: the cross of walls is three walls across and down. */
    assert_int_equal(cw, 3 * 256);
    assert_int_equal(ch, 3 * 256);
    for (int s = 0; s < cfg.node_count; s++) {
        const cluster_node_screen *ns = &cfg.nodes[s].screens[0];
        const cluster_screen *sc = &cfg.screens[ns->screen];
        uint8_t c[3];
        screen_colour(ns->screen, c);
        /* The picture: the corner opposite the label. */
        int x = sc->overview[0] + ns->width - 2, y = sc->overview[1] + ns->height - 2;
        assert_memory_equal(canvas + ((size_t)y * cw + x) * 3, c, 3);
        int match, want;
        label_pixels(canvas, cw, ch, s, &match, &want);
        printf("%-10s label: %d of %d text pixels\n", sc->name, match, want);
        assert_true(want > 100);
        assert_int_equal(match, want);
    }
    /* Without one image: the file, in one line; live, its place black and labelled. */
    char gone[1100];
    snprintf(gone, sizeof gone, "%s/front-r-left.png", dir);
    assert_int_equal(unlink(gone), 0);
    assert_int_equal(overview_compose(&cfg, dir, out, err, sizeof err), -1);
    assert_non_null(strstr(err, "front-r-left.png"));
    assert_null(strchr(err, '\n'));
    memset(canvas, 0x55, (size_t)cw * ch * 3);
    assert_int_equal(overview_draw(&cfg, dir, 1, canvas, cw, ch, err, sizeof err), 9);
    int fr = cluster_config_find_screen(&cfg, "front-r"), match, want;
    const cluster_screen *sc = &cfg.screens[fr];
    static const uint8_t black[3] = {0, 0, 0};
    assert_memory_equal(canvas + ((size_t)(sc->overview[1] + 200) * cw + sc->overview[0] + 100) * 3, black, 3);
    label_pixels(canvas, cw, ch, cluster_config_find_node(&cfg, "n02"), &match, &want);
    assert_int_equal(match, want);
    free(canvas);
    for (int s = 0; s < cfg.screen_count; s++) {
        char path[1100];
        snprintf(path, sizeof path, "%s/%s-left.png", dir, cfg.screens[s].name);
        unlink(path);
    }
    unlink(out);
    rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cave5_overview),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
