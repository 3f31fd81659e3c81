/* warp files: MPCDI archives (built here with libzip and libpng, as a calibration tool
 * writes them) and cavelight warp meshes read into the warp_map they describe; every
 * malformed or mismatched file is refused in one line naming the file and the part. */
#include <math.h>
#include <png.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zip.h>
#include <zlib.h>
#include <cmocka.h>

#include "warp/mpcdi.h"
#include "warp/warp_mesh.h"

typedef struct blob {
    const char *name;
    uint8_t *data;
    size_t len;
} blob;

/* A zip of the members, in memory (free() it). */
static uint8_t *make_zip(const blob *m, int n, size_t *len)
{
    zip_error_t ze;
    zip_error_init(&ze);
    zip_source_t *src = zip_source_buffer_create(NULL, 0, 0, &ze);
    zip_t *z = zip_open_from_source(src, ZIP_TRUNCATE, &ze);
    if (z)
        zip_source_keep(src); /* read back after zip_close() */
    assert_non_null(z);
    for (int i = 0; i < n; i++)
        assert_true(zip_file_add(z, m[i].name, zip_source_buffer(z, m[i].data, m[i].len, 0), 0) >= 0);
    assert_int_equal(zip_close(z), 0);
    assert_int_equal(zip_source_open(src), 0);
    zip_source_seek(src, 0, SEEK_END);
    *len = (size_t)zip_source_tell(src);
    zip_source_seek(src, 0, SEEK_SET);
    uint8_t *out = malloc(*len);
    assert_int_equal(zip_source_read(src, out, *len), (zip_int64_t)*len);
    zip_source_close(src);
    zip_source_free(src);
    zip_error_fini(&ze);
    return out;
}

/* w x h samples of c channels, little-endian, rows bottom first: value(i, j, k). */
static blob pfm(const char *name, int w, int h, int c, float (*value)(int, int, int))
{
    char head[64];
    int n = snprintf(head, sizeof head, "%s\n%d %d\n-1.0\n", c == 3 ? "PF" : "Pf", w, h);
    blob b = {name, malloc((size_t)n + (size_t)w * h * c * 4), (size_t)n + (size_t)w * h * c * 4};
    memcpy(b.data, head, (size_t)n);
    float *f = (float *)(b.data + n);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++)
            for (int k = 0; k < c; k++)
                memcpy(&f[((size_t)j * w + i) * c + k], &(float){value(i, j, k)}, 4);
    return b;
}

/* A grey or RGB PNG, 8 or 16 bits, of value v(x, y) in 0..1, rows top first. */
static blob png(const char *name, int w, int h, int channels, int bits, float (*v)(int, int))
{
    png_image img = {.version = PNG_IMAGE_VERSION, .width = (png_uint_32)w, .height = (png_uint_32)h,
                     .format = (channels == 3 ? PNG_FORMAT_RGB : PNG_FORMAT_GRAY) |
                               (bits == 16 ? PNG_FORMAT_FLAG_LINEAR : 0)};
    size_t n = (size_t)w * h * channels;
    void *px = malloc(n * (size_t)(bits / 8));
    for (size_t i = 0; i < n; i++) {
        int x = (int)(i / channels) % w, y = (int)(i / channels) / w;
        if (bits == 16)
            ((uint16_t *)px)[i] = (uint16_t)lroundf(v(x, y) * 65535);
        else
            ((uint8_t *)px)[i] = (uint8_t)lroundf(v(x, y) * 255);
    }
    png_alloc_size_t size = 0;
    assert_true(png_image_write_to_memory(&img, NULL, &size, 0, px, 0, NULL));
    blob b = {name, malloc(size), size};
    assert_true(png_image_write_to_memory(&img, b.data, &size, 0, px, 0, NULL));
    free(px);
    return b;
}

/* The warp a 2d grid holds: u = 0.2 + 0.5 x, v = y at the cell centres. */
static float uv_sample(int i, int j, int k)
{
    return k == 0 ? 0.2f + 0.5f * (i + 0.5f) / 3 : k == 1 ? (j + 0.5f) / 2 : NAN;
}

static float xyz_mm(int i, int j, int k)
{
    return k == 0 ? 1000.0f * i : k == 1 ? 1000.0f * j : -2000.0f;
}

static float ramp(int x, int y)
{
    (void)y;
    return x / 3.0f;
}

static const char *const XML_2D =
    "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
    "<MPCDI profile=\"2d\" geometry=\"1\" color=\"2\" version=\"2.0\"><display>\n"
    " <buffer id=\"b1\" xResolution=\"1920\" yResolution=\"1200\">\n"
    "  <region id=\"p1\" x=\"0.5\" y=\"0.25\" xSize=\"0.5\" ySize=\"0.5\" xResolution=\"960\" yResolution=\"600\"/>\n"
    "  <region id=\"p2\" x=\"0\" y=\"0\" xSize=\"0.5\" ySize=\"1\" xResolution=\"960\" yResolution=\"1200\"/>\n"
    " </buffer></display><files>\n"
    " <fileset region=\"p1\"><geometryWarpFile><path>p1.pfm</path><interpolation>linear</interpolation>"
    "</geometryWarpFile><alphaMap><path>p1_alpha.png</path><componentDepth>1</componentDepth><bitDepth>16</bitDepth>"
    "<gammaEmbedded>2.2</gammaEmbedded></alphaMap><betaMap><path>p1_beta.png</path><componentDepth>3</componentDepth>"
    "<bitDepth>8</bitDepth></betaMap></fileset>\n"
    "</files></MPCDI>\n";

/* The 2d archive with the XML text given (or XML_2D) and the usual members. */
static uint8_t *archive(const char *xml, size_t *len)
{
    blob m[4] = {{"mpcdi.xml", (uint8_t *)strdup(xml ? xml : XML_2D), strlen(xml ? xml : XML_2D)},
                 pfm("p1.pfm", 3, 2, 3, uv_sample), png("p1_alpha.png", 4, 2, 1, 16, ramp),
                 png("p1_beta.png", 2, 2, 3, 8, ramp)};
    uint8_t *z = make_zip(m, 4, len);
    for (int i = 0; i < 4; i++)
        free(m[i].data);
    return z;
}

/* XML_2D with the first `from` replaced by `to`. */
static const char *edited(const char *from, const char *to)
{
    static char buf[4096];
    const char *at = strstr(XML_2D, from);
    assert_non_null(at);
    snprintf(buf, sizeof buf, "%.*s%s%s", (int)(at - XML_2D), XML_2D, to, at + strlen(from));
    return buf;
}

static void test_mpcdi_2d(void **state)
{
    (void)state;
    size_t len;
    uint8_t *z = archive(NULL, &len);
    warp_map m;
    char err[512] = "";
    if (mpcdi_parse(z, len, "wall.mpcdi", "p1", &m, err, sizeof err) != 0)
        fail_msg("%s", err);
    assert_int_equal(m.kind, WARP_UV_GRID);
    assert_int_equal(m.out_w, 960);
    assert_int_equal(m.out_h, 600);
    assert_int_equal(m.place[0], 960); /* x 0.5 of 1920 */
    assert_int_equal(m.place[1], 300); /* y 0.25 of 1200, from the top */
    assert_int_equal(m.grid_w, 3);
    assert_int_equal(m.grid_h, 2);
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 3; i++) {
            assert_float_equal(m.grid[(j * 3 + i) * 3 + 0], uv_sample(i, j, 0), 1e-7);
            assert_float_equal(m.grid[(j * 3 + i) * 3 + 1], uv_sample(i, j, 1), 1e-7);
            assert_float_equal(m.grid[(j * 3 + i) * 3 + 2], 0, 0); /* the error channel's NaN is dropped */
        }
    assert_int_equal(m.alpha.width, 4);
    assert_int_equal(m.alpha.channels, 1);
    assert_float_equal(m.alpha.values[3], 1.0f, 1e-6);
    assert_float_equal(m.alpha.values[1], 1 / 3.0f, 1e-4); /* 16 bits */
    assert_float_equal(m.alpha_gamma, 2.2f, 1e-6);
    assert_int_equal(m.beta.channels, 3);
    assert_float_equal(m.beta.values[3], 1 / 3.0f, 0.5 / 255); /* pixel (1, 0)'s red, 8 bits */
    warp_map_free(&m);
    free(z);
}

static void test_mpcdi_3d(void **state)
{
    (void)state;
    const char *xml =
        "<?xml version=\"1.0\"?><mpcdi PROFILE=\"3d\" geometry=\"1\" color=\"1\" version=\"2.0\"><display>"
        "<buffer id=\"b\"><REGION id=\"only\" x=\"0\" y=\"0\" xsize=\"1\" ysize=\"1\" xresolution=\"64\" "
        "yresolution=\"48\"><frustum><yaw>0</yaw><pitch>0</pitch><roll>0</roll><leftAngle>-30</leftAngle>"
        "<rightAngle>30</rightAngle><downAngle>-20</downAngle><upAngle>20</upAngle></frustum></REGION></buffer>"
        "</display><files><fileset region=\"only\"><geometryWarpFile><geometricUnit>mm</geometricUnit>"
        "<path>w.pfm</path></geometryWarpFile><alphaMap><path>a.png</path><componentDepth>1</componentDepth>"
        "<bitDepth>8</bitDepth><gammaEmbedded>1</gammaEmbedded></alphaMap></fileset></files></mpcdi>";
    blob m[3] = {{"mpcdi.xml", (uint8_t *)strdup(xml), strlen(xml)}, pfm("w.pfm", 2, 2, 3, xyz_mm),
                 png("a.png", 2, 2, 1, 8, ramp)};
    size_t len;
    uint8_t *z = make_zip(m, 3, &len);
    warp_map w;
    char err[512] = "";
    /* Names without case (MPCDI's rule), the only region without naming it, points in metres. */
    if (mpcdi_parse(z, len, "dome.mpcdi", NULL, &w, err, sizeof err) != 0)
        fail_msg("%s", err);
    assert_int_equal(w.kind, WARP_POINT_GRID);
    assert_int_equal(w.out_w, 64);
    assert_float_equal(w.grid[3 * 3 + 0], 1.0f, 1e-6);
    assert_float_equal(w.grid[3 * 3 + 1], 1.0f, 1e-6);
    assert_float_equal(w.grid[3 * 3 + 2], -2.0f, 1e-6);
    warp_map_free(&w);
    free(z);
    for (int i = 0; i < 3; i++)
        free(m[i].data);
}

/* Each case: what is broken, the start of the one-line refusal. */
static void refused(const uint8_t *z, size_t len, const char *region, const char *want)
{
    warp_map m;
    char err[512] = "";
    assert_int_equal(mpcdi_parse(z, len, "wall.mpcdi", region, &m, err, sizeof err), -1);
    if (!strstr(err, want))
        fail_msg("expected \"%s\" in: %s", want, err);
    assert_null(strchr(err, '\n'));
    assert_null(m.grid); /* nothing left behind */
    assert_null(m.alpha.values);
}

static void refused_xml(const char *xml, const char *region, const char *want)
{
    size_t len;
    uint8_t *z = archive(xml, &len);
    refused(z, len, region, want);
    free(z);
}

static void test_mpcdi_refused(void **state)
{
    (void)state;
    refused((const uint8_t *)"PK\3\4 not really", 16, "p1", "MPCDI wall.mpcdi: archive: not a zip archive");
    refused_xml("<MPCDI profile=\"2d\"><display>", "p1", "MPCDI wall.mpcdi: mpcdi.xml: not well-formed XML (line");
    refused_xml(edited("profile=\"2d\"", "profile=\"a3\""), "p1",
                "MPCDI wall.mpcdi: MPCDI tag: profile 'a3' is not supported (2d or 3d");
    refused_xml(XML_2D, "p9", "MPCDI wall.mpcdi: display: no region 'p9' (the file's regions: p1, p2)");
    refused_xml(XML_2D, NULL, "MPCDI wall.mpcdi: display: 2 regions (p1, p2): name the one");
    refused_xml(edited("xResolution=\"960\" yResolution=\"600\"", "yResolution=\"600\""), "p1",
                "MPCDI wall.mpcdi: region p1: no xResolution");
    refused_xml(edited("xSize=\"0.5\"", "xSize=\"1.5\""), "p1", "region p1: xSize '1.5' is not a number in [1e-06, 1]");
    refused_xml(edited("region=\"p1\"", "region=\"p2\""), "p1", "region p1: fileset: missing");
    refused_xml(edited("<path>p1.pfm</path>", "<path>P1.pfm</path>"), "p1",
                "region p1: fileset: P1.pfm is not in the archive");
    refused_xml(edited("<componentDepth>1</componentDepth>", "<componentDepth>3</componentDepth>"), "p1",
                "region p1: fileset: alphaMap p1_alpha.png: 1 channel of 16 bits, but the XML says componentDepth 3");
    refused_xml(edited("<gammaEmbedded>2.2</gammaEmbedded>", ""), "p1", "region p1: fileset: no gammaEmbedded");
    refused_xml(edited("<alphaMap><path>p1_alpha.png</path><componentDepth>1</componentDepth><bitDepth>16</bitDepth>"
                       "<gammaEmbedded>2.2</gammaEmbedded></alphaMap>", ""),
                "p1", "region p1: fileset: no alphaMap (it is required)");
    refused_xml(edited("profile=\"2d\"", "profile=\"3d\""), "p1", "region p1: no frustum (profile 3d needs one)");
    /* Members that are not what the XML says they are. */
    size_t len;
    blob m[3] = {{"mpcdi.xml", (uint8_t *)strdup(XML_2D), strlen(XML_2D)}, pfm("p1.pfm", 2, 2, 1, uv_sample),
                 png("p1_alpha.png", 1, 1, 1, 16, ramp)};
    uint8_t *z = make_zip(m, 3, &len);
    refused(z, len, "p1", "region p1: fileset: geometryWarpFile p1.pfm: 2 x 2 samples of 1 channel: at least 2 x 2 of 3");
    free(z);
    free(m[1].data);
    m[1] = pfm("p1.pfm", 3, 2, 3, uv_sample);
    m[1].len -= 5; /* truncated */
    z = make_zip(m, 3, &len);
    refused(z, len, "p1", "geometryWarpFile p1.pfm: PFM truncated");
    free(z);
    m[1].len += 5;
    z = make_zip(m, 3, &len);
    refused(z, len, "p1", "alphaMap p1_alpha.png: 1 x 1 pixels, at least 2 x 2 needed");
    free(z);
    refused(m[0].data, m[0].len, "p1", "archive: not a zip archive");
    z = make_zip(m + 1, 2, &len);
    refused(z, len, "p1", "MPCDI wall.mpcdi: mpcdi.xml: mpcdi.xml is not in the archive");
    free(z);
    for (int i = 0; i < 3; i++)
        free(m[i].data);
    warp_map w;
    char err[256];
    assert_int_equal(mpcdi_load("/nonexistent/x.mpcdi", "p1", &w, err, sizeof err), -1);
    assert_non_null(strstr(err, "MPCDI /nonexistent/x.mpcdi: cannot open"));
}

/* A PNG that claims w x h pixels: a tiny one's IHDR rewritten (its CRC too), no more data. */
static blob png_claiming(const char *name, uint32_t w, uint32_t h)
{
    blob b = png(name, 2, 2, 1, 8, ramp);
    for (int k = 0; k < 4; k++) {
        b.data[16 + k] = (uint8_t)(w >> (24 - 8 * k));
        b.data[20 + k] = (uint8_t)(h >> (24 - 8 * k));
    }
    uLong crc = crc32(0, b.data + 12, 17);
    for (int k = 0; k < 4; k++)
        b.data[29 + k] = (uint8_t)(crc >> (24 - 8 * k));
    return b;
}

/* Decompression bombs: grids and maps larger than the projector image the XML declares, or
 * than the memory limit, are refused from their headers; a warp member is never inflated
 * past what a sample per projector pixel takes. And libxml2's own depth limit holds (256,
 * as long as XML_PARSE_HUGE is not set). */
static void test_mpcdi_bombs(void **state)
{
    (void)state;
    size_t len;
    const char *big = edited("xResolution=\"960\" yResolution=\"600\"", "xResolution=\"16384\" yResolution=\"16384\"");
    char xml[4096];
    snprintf(xml, sizeof xml, "%s", big);
    blob m[3] = {{"mpcdi.xml", (uint8_t *)strdup(xml), strlen(xml)}, pfm("p1.pfm", 3, 2, 3, uv_sample),
                 png_claiming("p1_alpha.png", 16384, 16384)};
    uint8_t *z = make_zip(m, 3, &len);
    refused(z, len, "p1", "alphaMap p1_alpha.png: PNG size 16384 x 16384 x 1 values is over the limit of 67108864");
    free(z);
    free(m[0].data);
    m[0] = (blob){"mpcdi.xml", (uint8_t *)strdup(XML_2D), strlen(XML_2D)};
    free(m[2].data);
    m[2] = png_claiming("p1_alpha.png", 1000, 4);
    z = make_zip(m, 3, &len);
    refused(z, len, "p1", "alphaMap p1_alpha.png: PNG size 1000 x 4 is larger than the 960 x 600 projector image");
    free(z);
    free(m[1].data);
    m[1] = pfm("p1.pfm", 1000, 2, 3, uv_sample);
    z = make_zip(m, 3, &len);
    refused(z, len, "p1", "geometryWarpFile p1.pfm: PFM size 1000 x 2 is larger than the 960 x 600 projector image");
    free(z);
    /* a small grid followed by 7 MB that compress to nothing */
    free(m[1].data);
    m[1] = pfm("p1.pfm", 3, 2, 3, uv_sample);
    size_t pad = 7u << 20;
    m[1].data = realloc(m[1].data, m[1].len + pad);
    memset(m[1].data + m[1].len, 0, pad);
    m[1].len += pad;
    z = make_zip(m, 3, &len);
    refused(z, len, "p1", "p1.pfm is larger than 6912128 bytes, the most it may hold");
    free(z);
    for (int i = 0; i < 3; i++)
        free(m[i].data);
    char deep[8192];
    int n = snprintf(deep, sizeof deep, "<MPCDI profile=\"2d\"><display>");
    for (int i = 0; i < 300; i++)
        n += snprintf(deep + n, sizeof deep - (size_t)n, "<a>");
    refused_xml(deep, "p1", "Excessive depth in document: 256");
}

static const char *const MESH =
    "cavelight-warp-mesh 1\n"
    "# a keystone: the top edge is pulled in\n"
    "grid 2 2\n"
    "output 320 200\n"
    "\n"
    "0 0 0 0 1\n"
    "1 0 1 0 0.5\n"
    "0.1 1 0 1 1\n"
    "0.9 1 1 1 0.5\n";

static void test_mesh(void **state)
{
    (void)state;
    warp_map m;
    char err[256] = "";
    if (warp_mesh_parse(MESH, strlen(MESH), "k.warp", &m, err, sizeof err) != 0)
        fail_msg("%s", err);
    assert_int_equal(m.kind, WARP_MESH);
    assert_int_equal(m.mesh_cols, 2);
    assert_int_equal(m.mesh_rows, 2);
    assert_int_equal(m.out_w, 320);
    assert_int_equal(m.out_h, 200);
    assert_int_equal(m.place[0], -1);
    assert_float_equal(m.mesh[2 * 5 + 0], 0.1f, 1e-7);
    assert_float_equal(m.mesh[3 * 5 + 4], 0.5f, 1e-7);
    warp_map_free(&m);
}

static void mesh_refused(const char *text, const char *want)
{
    warp_map m;
    char err[256] = "";
    assert_int_equal(warp_mesh_parse(text, strlen(text), "k.warp", &m, err, sizeof err), -1);
    if (!strstr(err, want))
        fail_msg("expected \"%s\" in: %s", want, err);
    assert_null(strchr(err, '\n'));
    assert_null(m.mesh);
}

static void test_mesh_refused(void **state)
{
    (void)state;
    mesh_refused("", "warp mesh k.warp: line 1: empty: no 'cavelight-warp-mesh 1' line");
    mesh_refused("P3\n2 2\n", "warp mesh k.warp: line 1: not a warp mesh: the first line must be 'cavelight-warp-mesh 1'");
    mesh_refused("cavelight-warp-mesh 1\n0 0 0 0 1\n", "line 2: a vertex before the 'grid COLS ROWS' line");
    mesh_refused("cavelight-warp-mesh 1\ngrid 1 2\n", "line 2: grid 1 is outside 2..1024");
    mesh_refused("cavelight-warp-mesh 1\ngrid 2 2\n0 0 0 0 1\n1 0 1 0 1.5\n", "line 4: w 1.5 is outside 0..1");
    mesh_refused("cavelight-warp-mesh 1\ngrid 2 2\n0 0 0 0\n", "line 3: a vertex is five numbers: x y u v w (found 4");
    mesh_refused("cavelight-warp-mesh 1\ngrid 2 2\n0 0 0 zero 1\n", "line 3: v 'zero' is not a number");
    mesh_refused("cavelight-warp-mesh 1\ngrid 2 2\n0 0 0 0 1\n", "line 4: the file ends after 1 of the grid's 2 x 2");
    mesh_refused("cavelight-warp-mesh 1\ngrid 2 2\n0 0 0 0 1\noutput 4 4\n",
                 "line 4: 'output' after the first vertex (settings come first)");
    char five[200];
    snprintf(five, sizeof five, "%s0 0 0 0 1\n", MESH);
    mesh_refused(five, "line 10: more than the grid's 2 x 2 vertex lines");
    warp_map m;
    char err[256];
    assert_int_equal(warp_mesh_load("/nonexistent/k.warp", &m, err, sizeof err), -1);
    assert_non_null(strstr(err, "warp mesh /nonexistent/k.warp: cannot open"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mpcdi_2d),     cmocka_unit_test(test_mpcdi_3d),
        cmocka_unit_test(test_mpcdi_refused), cmocka_unit_test(test_mpcdi_bombs),
        cmocka_unit_test(test_mesh),
        cmocka_unit_test(test_mesh_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
