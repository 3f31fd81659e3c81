/* libFuzzer target: projector files, which a node reads at start from wherever its config
 * points. The same bytes go
 *   - to mpcdi_parse() as a whole archive (libzip's checks first),
 *   - as the members of an archive built here, so that mutations reach the XML, PFM and PNG
 *     readers past the zip's CRCs: "@@NAME\n" starts a member, the bytes before the first
 *     one are mpcdi.xml; the regions "p1", "left" and the only one are asked for,
 *   - to warp_mesh_parse() as a warp mesh,
 *   - to the PFM and PNG decoders directly.
 * A map that loads must be one the presentation can draw: sizes and channels in range,
 * every grid or mesh value finite or WARP_UNKNOWN. Built with clang -fsanitize=fuzzer,
 * address,undefined by CMake when clang is present. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zip.h>

#include "warp/mpcdi.h"
#include "warp/warp_mesh.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_map(const warp_map *m)
{
    if (m->out_w < 0 || m->out_h < 0 || m->out_w > 16384 || m->out_h > 16384)
        abort();
    if (m->kind == WARP_UV_GRID || m->kind == WARP_POINT_GRID) {
        if (m->grid_w < 2 || m->grid_h < 2 || !m->grid || m->grid_w > m->out_w || m->grid_h > m->out_h)
            abort(); /* no larger than the projector image the file declares */
        for (size_t i = 0; i < (size_t)m->grid_w * m->grid_h * 3; i++)
            if (!isfinite(m->grid[i]))
                abort();
    }
    if (m->kind == WARP_MESH) {
        if (m->mesh_cols < 2 || m->mesh_rows < 2 || !m->mesh)
            abort();
        for (size_t i = 0; i < (size_t)m->mesh_cols * m->mesh_rows * 5; i++)
            if (!isfinite(m->mesh[i]) || (i % 5 == 4 && (m->mesh[i] < 0 || m->mesh[i] > 1)))
                abort();
    }
    const warp_blend_map *maps[2] = {&m->alpha, &m->beta};
    for (int k = 0; k < 2; k++)
        if (maps[k]->values && (maps[k]->width < 2 || maps[k]->height < 2 ||
                                (maps[k]->channels != 1 && maps[k]->channels != 3) ||
                                (m->kind != WARP_MESH && (maps[k]->width > m->out_w || maps[k]->height > m->out_h))))
            abort();
}

static void parse(const void *zip, size_t len)
{
    static const char *const regions[3] = {"p1", "left", NULL};
    for (int r = 0; r < 3; r++) {
        warp_map m;
        char err[512];
        if (mpcdi_parse(zip, len, "fuzz.mpcdi", regions[r], &m, err, sizeof err) == 0) {
            check_map(&m);
            warp_map_free(&m);
        } else if (!memchr(err, 0, sizeof err) || strchr(err, '\n')) {
            fprintf(stderr, "not one line: %.*s\n", (int)sizeof err, err);
            abort();
        }
    }
}

/* The input's members ("@@NAME\n" each) zipped, stored, then parsed. */
static void parse_members(const uint8_t *data, size_t size)
{
    zip_error_t ze;
    zip_error_init(&ze);
    zip_source_t *src = zip_source_buffer_create(NULL, 0, 0, &ze);
    zip_t *z = zip_open_from_source(src, ZIP_TRUNCATE, &ze);
    if (z)
        zip_source_keep(src); /* read back after zip_close() */
    const uint8_t *at = data, *end = data + size;
    char name[64] = "mpcdi.xml";
    while (z && at <= end) {
        const uint8_t *next = at;
        while (next + 3 <= end && !(next[0] == '@' && next[1] == '@' && (next == data || next[-1] == '\n')))
            next++;
        if (next + 3 > end)
            next = end;
        zip_source_t *s = zip_source_buffer(z, at, (zip_uint64_t)(next - at), 0);
        zip_int64_t i = s ? zip_file_add(z, name, s, ZIP_FL_OVERWRITE) : -1;
        if (i < 0)
            zip_source_free(s);
        else
            zip_set_file_compression(z, (zip_uint64_t)i, ZIP_CM_STORE, 0);
        if (next == end)
            break;
        const uint8_t *nl = memchr(next, '\n', (size_t)(end - next));
        size_t n = nl ? (size_t)(nl - next - 2) : 0;
        snprintf(name, sizeof name, "%.*s", (int)(n < sizeof name ? n : sizeof name - 1), (const char *)next + 2);
        if (!nl || !name[0])
            break;
        at = nl + 1;
    }
    int closed = z && zip_close(z) == 0;
    if (z && !closed)
        zip_discard(z);
    if (closed && zip_source_open(src) == 0) {
        zip_source_seek(src, 0, SEEK_END);
        zip_int64_t len = zip_source_tell(src);
        zip_source_seek(src, 0, SEEK_SET);
        void *buf = len > 0 ? malloc((size_t)len) : NULL;
        if (buf && zip_source_read(src, buf, (zip_uint64_t)len) == len)
            parse(buf, (size_t)len);
        free(buf);
        zip_source_close(src);
    }
    zip_source_free(src);
    zip_error_fini(&ze);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    parse(data, size);
    parse_members(data, size);
    warp_map m;
    char err[512];
    if (warp_mesh_parse((const char *)data, size, "fuzz.warp", &m, err, sizeof err) == 0) {
        check_map(&m);
        warp_map_free(&m);
    }
    int w, h, c, bits;
    float *v = NULL;
    if (warp_decode_pfm(data, size, 0, 0, &w, &h, &c, &v, err, sizeof err) == 0)
        free(v);
    warp_blend_map b;
    if (warp_decode_png(data, size, 0, 0, &b, &bits, err, sizeof err) == 0)
        free(b.values);
    return 0;
}
