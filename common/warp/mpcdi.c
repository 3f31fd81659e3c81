/* mpcdi: see mpcdi.h. */
#include "warp/mpcdi.h"

#include <libxml/parser.h>
#include <libxml/tree.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zip.h>

#include "base/textfile.h"

/* Caps on what one archive may hold: the XML, one warp grid, one blend map. */
enum { XML_MAX = 4 << 20, PFM_MAX = 256 << 20, PNG_MAX = 64 << 20, SIDE_MAX = 16384,
       PFM_HEADER_MAX = 128 };
/* The archive itself: its members' caps, stored, and room to spare. */
enum { FILE_MAX = 512 << 20 };

typedef struct ctx {
    const char *name;
    char *err;
    size_t errlen;
    zip_t *zip;
    int three_d; /* profile 3d */
} ctx;

static int fail(ctx *c, const char *part, const char *fmt, ...)
{
    char msg[320];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    snprintf(c->err, c->errlen, "MPCDI %s: %s: %s", c->name, part, msg);
    for (char *ch = c->err; *ch; ch++) /* quoted file content stays on one line */
        if ((unsigned char)*ch < ' ')
            *ch = '?';
    return -1;
}

/* ---- XML: names without case, values with it (MPCDI 3.5.2) ------------------------------ */

static int named(const xmlNode *n, const char *name)
{
    return n && n->type == XML_ELEMENT_NODE && xmlStrcasecmp(n->name, (const xmlChar *)name) == 0;
}

static xmlNode *child(const xmlNode *n, const char *name)
{
    for (xmlNode *k = n ? n->children : NULL; k; k = k->next)
        if (named(k, name))
            return k;
    return NULL;
}

static xmlNode *next_named(xmlNode *n, const char *name)
{
    for (n = n ? n->next : NULL; n; n = n->next)
        if (named(n, name))
            return n;
    return NULL;
}

static const char *attr(const xmlNode *n, const char *name)
{
    for (const xmlAttr *a = n->properties; a; a = a->next)
        if (xmlStrcasecmp(a->name, (const xmlChar *)name) == 0)
            return a->children && a->children->content ? (const char *)a->children->content : "";
    return NULL;
}

/* An element's text, without surrounding blanks, into buf; NULL when the element is absent. */
static const char *text(const xmlNode *parent, const char *tag, char *buf, size_t cap)
{
    const xmlNode *e = child(parent, tag);
    if (!e)
        return NULL;
    xmlChar *s = xmlNodeGetContent(e);
    const char *p = s ? (const char *)s : "";
    while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n')
        p++;
    snprintf(buf, cap, "%s", p);
    xmlFree(s);
    for (size_t n = strlen(buf); n > 0 && (buf[n - 1] == ' ' || buf[n - 1] == '\t' || buf[n - 1] == '\r' ||
                                           buf[n - 1] == '\n'); n--)
        buf[n - 1] = 0;
    return buf;
}

/* A number from an attribute or element text within [lo, hi]; 0 or -1 after fail(). */
static int number(ctx *c, const char *part, const char *key, const char *s, double lo, double hi,
                  double *out)
{
    char *end = NULL;
    double v = s ? strtod(s, &end) : NAN;
    if (!s)
        return fail(c, part, "no %s", key);
    if (end == s || *end || !isfinite(v) || v < lo || v > hi)
        return fail(c, part, "%s '%.40s' is not a number in [%g, %g]", key, s, lo, hi);
    *out = v;
    return 0;
}

static int whole(ctx *c, const char *part, const char *key, const char *s, int lo, int hi, int *out)
{
    double v = 0;
    if (number(c, part, key, s, lo, hi, &v))
        return -1;
    if (v != floor(v))
        return fail(c, part, "%s %g is not a whole number", key, v);
    *out = (int)v;
    return 0;
}

/* ---- the archive ------------------------------------------------------------------------- */

/* A member's bytes (free() them), at most cap; NULL after fail(). */
static uint8_t *member(ctx *c, const char *part, const char *path, size_t cap, size_t *len)
{
    zip_int64_t i = zip_name_locate(c->zip, path, 0);
    if (i < 0) {
        fail(c, part, "%s is not in the archive", path);
        return NULL;
    }
    zip_file_t *f = zip_fopen_index(c->zip, (zip_uint64_t)i, 0);
    if (!f) {
        fail(c, part, "%s cannot be opened (libzip: %s)", path, zip_strerror(c->zip));
        return NULL;
    }
    /* Grown as the data comes, never by what the archive claims: a member is at most cap. */
    size_t size = 0, have = 0;
    uint8_t *buf = NULL;
    int ok = 1;
    for (;;) {
        if (have == size) {
            size_t grown = size ? 2 * size : 65536;
            /* not xalloc: a file's size (at most cap): refused naming the file */
            uint8_t *b = size <= cap ? realloc(buf, grown < cap + 1 ? grown : cap + 1) : NULL;
            if (!b) {
                if (size > cap)
                    fail(c, part, "%s is larger than %zu bytes, the most it may hold", path, cap);
                else
                    fail(c, part, "out of memory for %s", path);
                ok = 0;
                break;
            }
            buf = b;
            size = grown < cap + 1 ? grown : cap + 1;
        }
        zip_int64_t n = zip_fread(f, buf + have, size - have);
        if (n < 0) {
            fail(c, part, "%s cannot be read (libzip: %s)", path, zip_file_strerror(f));
            ok = 0;
            break;
        }
        if (n == 0)
            break;
        have += (size_t)n;
    }
    zip_fclose(f);
    if (!ok) {
        free(buf);
        return NULL;
    }
    *len = have;
    return buf;
}

/* ---- region ------------------------------------------------------------------------------- */

/* The wanted region (or the only one) and its buffer; NULL after fail(). */
static xmlNode *find_region(ctx *c, xmlNode *display, const char *want, xmlNode **buffer)
{
    char ids[160] = "";
    int count = 0;
    xmlNode *only = NULL;
    for (xmlNode *b = child(display, "buffer"); b; b = next_named(b, "buffer"))
        for (xmlNode *r = child(b, "region"); r; r = next_named(r, "region")) {
            const char *id = attr(r, "id");
            if (!id)
                return fail(c, "display", "a region has no id"), NULL;
            if (want && *want && strcmp(id, want) == 0) {
                *buffer = b;
                return r;
            }
            size_t used = strlen(ids);
            snprintf(ids + used, sizeof ids - used, "%s%s", count ? ", " : "", id);
            count++;
            only = r;
            *buffer = b;
        }
    if (want && *want)
        return fail(c, "display", "no region '%s' (the file's regions: %s)", want, count ? ids : "none"), NULL;
    if (count != 1)
        return fail(c, "display", "%d regions (%s): name the one this screen shows (\"region\")", count,
                    count ? ids : "none"), NULL;
    return only;
}

/* 3d: the frustum must be there and sane; the view itself comes from the cluster config. */
static int check_frustum(ctx *c, const char *part, const xmlNode *region)
{
    const xmlNode *f = child(region, "frustum");
    if (!f)
        return fail(c, part, "no frustum (profile 3d needs one)");
    static const char *const tags[7] = {"yaw", "pitch", "roll", "leftAngle", "rightAngle", "downAngle", "upAngle"};
    double v[7];
    char buf[64];
    for (int i = 0; i < 7; i++)
        if (number(c, part, tags[i], text(f, tags[i], buf, sizeof buf), i < 3 ? -360 : -89.9, i < 3 ? 360 : 89.9,
                   &v[i]))
            return -1;
    if (!(v[3] < v[4]) || !(v[5] < v[6]))
        return fail(c, part, "frustum: leftAngle must be less than rightAngle and downAngle less than upAngle");
    return 0;
}

/* The region's size and place; the projector image is its resolution. */
static int read_region(ctx *c, const char *part, const xmlNode *buffer, const xmlNode *region, warp_map *m)
{
    double x = 0, y = 0, xs = 1, ys = 1;
    int bw = 0, bh = 0;
    if (number(c, part, "x", attr(region, "x"), 0, 1, &x) || number(c, part, "y", attr(region, "y"), 0, 1, &y) ||
        number(c, part, "xSize", attr(region, "xSize"), 1e-6, 1, &xs) ||
        number(c, part, "ySize", attr(region, "ySize"), 1e-6, 1, &ys) ||
        whole(c, part, "xResolution", attr(region, "xResolution"), 1, SIDE_MAX, &m->out_w) ||
        whole(c, part, "yResolution", attr(region, "yResolution"), 1, SIDE_MAX, &m->out_h))
        return -1;
    const char *sbw = attr(buffer, "xResolution"), *sbh = attr(buffer, "yResolution");
    if ((sbw && whole(c, "buffer", "xResolution", sbw, 1, SIDE_MAX, &bw)) ||
        (sbh && whole(c, "buffer", "yResolution", sbh, 1, SIDE_MAX, &bh)))
        return -1;
    /* Without the buffer's size: the one the region's own size and share imply. */
    double width = bw ? bw : m->out_w / xs, height = bh ? bh : m->out_h / ys;
    m->place[0] = (int)lround(x * width);
    m->place[1] = (int)lround(y * height);
    return c->three_d ? check_frustum(c, part, region) : 0;
}

/* ---- files --------------------------------------------------------------------------------- */

static double unit_metres(const char *unit)
{
    static const struct { const char *name; double metres; } units[] = {
        {"mm", 0.001}, {"cm", 0.01}, {"dm", 0.1}, {"m", 1}, {"in", 0.0254}, {"ft", 0.3048},
        {"yd", 0.9144}, {"unknown", 1},
    };
    for (size_t i = 0; i < sizeof units / sizeof *units; i++)
        if (strcmp(unit, units[i].name) == 0)
            return units[i].metres;
    return 0;
}

static int read_warp(ctx *c, const char *part, const xmlNode *fileset, warp_map *m)
{
    const xmlNode *g = child(fileset, "geometryWarpFile");
    char path[256], unit[32];
    if (!g)
        return fail(c, part, "no geometryWarpFile (a warp is required)");
    if (!text(g, "path", path, sizeof path) || !*path)
        return fail(c, part, "geometryWarpFile has no path");
    double metres = 1;
    if (c->three_d && text(g, "geometricUnit", unit, sizeof unit) && !(metres = unit_metres(unit)))
        return fail(c, part, "geometricUnit '%.20s' is not one of mm, cm, dm, m, in, ft, yd, unknown", unit);
    /* At most a sample per projector pixel: the archive is not inflated past what that holds. */
    size_t len, cap = PFM_HEADER_MAX + 12 * (size_t)m->out_w * (size_t)m->out_h;
    uint8_t *bytes = member(c, part, path, cap < PFM_MAX ? cap : PFM_MAX, &len);
    if (!bytes)
        return -1;
    char why[200];
    int channels = 0, rc = warp_decode_pfm(bytes, len, m->out_w, m->out_h, &m->grid_w, &m->grid_h, &channels,
                                           &m->grid, why, sizeof why);
    free(bytes);
    if (rc)
        return fail(c, part, "geometryWarpFile %s: %s", path, why);
    if (channels != 3 || m->grid_w < 2 || m->grid_h < 2)
        return fail(c, part, "geometryWarpFile %s: %d x %d samples of %d channel%s: at least 2 x 2 of 3 needed",
                    path, m->grid_w, m->grid_h, channels, channels == 1 ? "" : "s");
    for (size_t i = 0; i < (size_t)m->grid_w * m->grid_h; i++) {
        float *s = m->grid + 3 * i;
        int known = isfinite(s[0]) && isfinite(s[1]) && (!c->three_d || isfinite(s[2]));
        for (int k = 0; k < 3; k++) /* 2d: the third channel is an error estimate, unused */
            s[k] = !known ? WARP_UNKNOWN : c->three_d ? (float)(s[k] * metres) : k < 2 ? s[k] : 0;
    }
    m->kind = c->three_d ? WARP_POINT_GRID : WARP_UV_GRID;
    return 0;
}

/* An alphaMap or betaMap: its PNG must be what the XML says. Absent: 0 when optional. */
static int read_map(ctx *c, const char *part, const xmlNode *fileset, const char *tag, int required,
                    int out_w, int out_h, warp_blend_map *out, float *gamma)
{
    const xmlNode *e = child(fileset, tag);
    if (!e)
        return required ? fail(c, part, "no %s (it is required)", tag) : 0;
    char path[256], buf[64], why[200];
    int depth, components, bits;
    if (!text(e, "path", path, sizeof path) || !*path)
        return fail(c, part, "%s has no path", tag);
    if (whole(c, part, "componentDepth", text(e, "componentDepth", buf, sizeof buf), 1, 3, &components) ||
        whole(c, part, "bitDepth", text(e, "bitDepth", buf, sizeof buf), 8, 16, &depth))
        return -1;
    double g = 1;
    if (gamma && number(c, part, "gammaEmbedded", text(e, "gammaEmbedded", buf, sizeof buf), 0.1, 10, &g))
        return -1;
    size_t len;
    uint8_t *bytes = member(c, part, path, PNG_MAX, &len);
    if (!bytes)
        return -1;
    int rc = warp_decode_png(bytes, len, out_w, out_h, out, &bits, why, sizeof why);
    free(bytes);
    if (rc)
        return fail(c, part, "%s %s: %s", tag, path, why);
    if (out->channels != components || bits != depth)
        return fail(c, part, "%s %s: %d channel%s of %d bits, but the XML says componentDepth %d, bitDepth %d",
                    tag, path, out->channels, out->channels == 1 ? "" : "s", bits, components, depth);
    if (out->width < 2 || out->height < 2)
        return fail(c, part, "%s %s: %d x %d pixels, at least 2 x 2 needed", tag, path, out->width, out->height);
    if (gamma)
        *gamma = (float)g;
    return 0;
}

static const xmlNode *find_fileset(const xmlNode *files, const char *id)
{
    for (xmlNode *f = child(files, "fileset"); f; f = next_named(f, "fileset")) {
        const char *r = attr(f, "region");
        if (r && strcmp(r, id) == 0)
            return f;
    }
    return NULL;
}

/* ---- the file ------------------------------------------------------------------------------ */

static int read_document(ctx *c, xmlDoc *doc, const char *want, warp_map *m)
{
    xmlNode *root = xmlDocGetRootElement(doc);
    if (!named(root, "MPCDI"))
        return fail(c, "mpcdi.xml", "the root element is <%.40s>, not <MPCDI>", root ? (const char *)root->name : "");
    const char *profile = attr(root, "profile");
    if (!profile)
        return fail(c, "MPCDI tag", "no profile attribute (2d or 3d)");
    if (strcmp(profile, "2d") && strcmp(profile, "3d"))
        return fail(c, "MPCDI tag", "profile '%.20s' is not supported (2d or 3d; a3 and sl are not)", profile);
    c->three_d = strcmp(profile, "3d") == 0;
    xmlNode *display = child(root, "display"), *buffer = NULL;
    if (!display)
        return fail(c, "mpcdi.xml", "no display element");
    xmlNode *region = find_region(c, display, want, &buffer);
    if (!region)
        return -1;
    const char *id = attr(region, "id");
    char part[160];
    snprintf(part, sizeof part, "region %.60s", id);
    if (read_region(c, part, buffer, region, m))
        return -1;
    const xmlNode *files = child(root, "files"), *fileset = find_fileset(files, id);
    snprintf(part, sizeof part, "region %.60s: fileset", id);
    if (!fileset)
        return fail(c, part, "missing (no fileset names this region under <files>)");
    m->alpha_gamma = 1;
    return read_warp(c, part, fileset, m) ||
           read_map(c, part, fileset, "alphaMap", 1, m->out_w, m->out_h, &m->alpha, &m->alpha_gamma) ||
           read_map(c, part, fileset, "betaMap", 0, m->out_w, m->out_h, &m->beta, NULL) ? -1 : 0;
}

int mpcdi_parse(const void *zip, size_t len, const char *name, const char *region, warp_map *out,
                char *err, size_t errlen)
{
    ctx c = {.name = name, .err = err, .errlen = errlen};
    memset(out, 0, sizeof *out);
    zip_error_t ze;
    zip_error_init(&ze);
    zip_source_t *src = zip_source_buffer_create(zip, len, 0, &ze);
    c.zip = src ? zip_open_from_source(src, ZIP_RDONLY, &ze) : NULL;
    if (!c.zip) {
        fail(&c, "archive", "not a zip archive (libzip: %s)", zip_error_strerror(&ze));
        zip_source_free(src);
        zip_error_fini(&ze);
        return -1;
    }
    zip_error_fini(&ze);
    size_t xml_len;
    uint8_t *xml = member(&c, "mpcdi.xml", "mpcdi.xml", XML_MAX, &xml_len);
    int rc = -1;
    if (xml) {
        xmlDoc *doc = xmlReadMemory((const char *)xml, (int)xml_len, "mpcdi.xml", NULL,
                                    XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
        if (!doc) {
            const xmlError *e = xmlGetLastError();
            char msg[96];
            snprintf(msg, sizeof msg, "%s", e && e->message ? e->message : "unknown error");
            msg[strcspn(msg, "\n")] = 0;
            fail(&c, "mpcdi.xml", "not well-formed XML (line %d: %s)", e ? e->line : 0, msg);
        } else {
            rc = read_document(&c, doc, region, out);
            xmlFreeDoc(doc);
        }
        free(xml);
    }
    zip_discard(c.zip);
    if (rc)
        warp_map_free(out);
    return rc;
}

int mpcdi_load(const char *path, const char *region, warp_map *out, char *err, size_t errlen)
{
    char why[128];
    size_t len = 0;
    char *bytes = textfile_read_max(path, FILE_MAX, &len, why, sizeof why);
    if (!bytes) {
        memset(out, 0, sizeof *out);
        snprintf(err, errlen, "MPCDI %s: %s", path, why);
        return -1;
    }
    int rc = mpcdi_parse(bytes, len, path, region, out, err, errlen);
    free(bytes);
    return rc;
}
