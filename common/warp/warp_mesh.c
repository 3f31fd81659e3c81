/* warp_mesh: see warp_mesh.h. */
#include "warp/warp_mesh.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/textfile.h"

enum { LINE_MAX_CHARS = 255, TOKENS_MAX = 6, SIDE_MAX = 1024, OUTPUT_MAX = 16384 };

#define MESH_MAGIC "cavelight-warp-mesh"

typedef struct parser {
    const char *name;
    int line;
    char *err;
    size_t errlen;
} parser;

static int fail(parser *p, const char *fmt, ...)
{
    char msg[200];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    snprintf(p->err, p->errlen, "warp mesh %s: line %d: %s", p->name, p->line, msg);
    for (char *ch = p->err; *ch; ch++) /* quoted file content stays on one line */
        if ((unsigned char)*ch < ' ')
            *ch = '?';
    return -1;
}

/* Splits line at blanks; returns the count, or -1 when there are more than TOKENS_MAX. */
static int tokens(char *line, char *tok[TOKENS_MAX])
{
    int n = 0;
    for (char *s = line; *s;) {
        while (*s == ' ' || *s == '\t' || *s == '\r')
            *s++ = 0;
        if (!*s)
            break;
        if (n == TOKENS_MAX)
            return -1;
        tok[n++] = s;
        while (*s && *s != ' ' && *s != '\t' && *s != '\r')
            s++;
    }
    return n;
}

static int number(parser *p, const char *what, const char *s, double lo, double hi, double *out)
{
    char *end;
    double v = strtod(s, &end);
    if (end == s || *end || !isfinite(v))
        return fail(p, "%s '%.30s' is not a number", what, s);
    if (v < lo || v > hi)
        return fail(p, "%s %g is outside %g..%g", what, v, lo, hi);
    *out = v;
    return 0;
}

/* "grid C R" or "output W H": two whole numbers in lo..hi. */
static int pair(parser *p, char **tok, int n, int lo, int hi, int out[2])
{
    if (n != 3)
        return fail(p, "'%s' takes two whole numbers", tok[0]);
    for (int i = 0; i < 2; i++) {
        double v = 0;
        if (number(p, tok[0], tok[1 + i], lo, hi, &v))
            return -1;
        if (v != floor(v))
            return fail(p, "%s %g is not a whole number", tok[0], v);
        out[i] = (int)v;
    }
    return 0;
}

/* One line after the header: a setting, or the next vertex. */
static int line_item(parser *p, char **tok, int n, warp_map *m, size_t *vertices)
{
    size_t total = (size_t)m->mesh_cols * m->mesh_rows;
    if (strcmp(tok[0], "grid") == 0 || strcmp(tok[0], "output") == 0) {
        if (*vertices)
            return fail(p, "'%s' after the first vertex (settings come first)", tok[0]);
        if (tok[0][0] == 'g') {
            if (m->mesh)
                return fail(p, "a second 'grid' line");
            int g[2];
            if (pair(p, tok, n, 2, SIDE_MAX, g))
                return -1;
            m->mesh_cols = g[0];
            m->mesh_rows = g[1];
            /* not xalloc: the mesh file's grid: refused in one line */
            m->mesh = calloc((size_t)g[0] * g[1] * 5, sizeof *m->mesh);
            return m->mesh ? 0 : fail(p, "out of memory for %d x %d vertices", g[0], g[1]);
        }
        int o[2];
        if (pair(p, tok, n, 1, OUTPUT_MAX, o))
            return -1;
        m->out_w = o[0];
        m->out_h = o[1];
        return 0;
    }
    if (!m->mesh)
        return fail(p, "a vertex before the 'grid COLS ROWS' line");
    if (*vertices == total)
        return fail(p, "more than the grid's %d x %d vertex lines", m->mesh_cols, m->mesh_rows);
    if (n != 5)
        return fail(p, "a vertex is five numbers: x y u v w (found %d items)", n);
    static const char *const names[5] = {"x", "y", "u", "v", "w"};
    float *v = m->mesh + 5 * *vertices;
    for (int i = 0; i < 5; i++) {
        double d = 0;
        if (number(p, names[i], tok[i], i < 4 ? -1e3 : 0, i < 4 ? 1e3 : 1, &d))
            return -1;
        v[i] = (float)d;
    }
    (*vertices)++;
    return 0;
}

int warp_mesh_parse(const char *text, size_t len, const char *name, warp_map *out, char *err,
                    size_t errlen)
{
    parser p = {.name = name, .err = err, .errlen = errlen};
    memset(out, 0, sizeof *out);
    out->kind = WARP_MESH;
    out->place[0] = out->place[1] = -1;
    out->alpha_gamma = 1;
    size_t vertices = 0, at = 0;
    int header = 0, rc = 0;
    while (rc == 0 && at < len) {
        p.line++;
        size_t end = at;
        while (end < len && text[end] != '\n')
            end++;
        char line[LINE_MAX_CHARS + 1], *tok[TOKENS_MAX];
        if (end - at > LINE_MAX_CHARS) {
            rc = fail(&p, "longer than %d characters", LINE_MAX_CHARS);
            break;
        }
        if (memchr(text + at, 0, end - at)) {
            rc = fail(&p, "holds a NUL byte");
            break;
        }
        memcpy(line, text + at, end - at);
        line[end - at] = 0;
        at = end + 1;
        if (line[strspn(line, " \t\r")] == '#')
            continue;
        int n = tokens(line, tok);
        if (n < 0)
            rc = fail(&p, "more than %d items", TOKENS_MAX);
        else if (n == 0)
            continue;
        else if (header)
            rc = line_item(&p, tok, n, out, &vertices);
        else if (n == 2 && strcmp(tok[0], MESH_MAGIC) == 0 && strcmp(tok[1], "1") == 0)
            header = 1;
        else
            rc = fail(&p, "not a warp mesh: the first line must be '" MESH_MAGIC " 1'");
    }
    if (rc == 0 && (!header || !out->mesh)) {
        p.line++;
        rc = fail(&p, header ? "the file ends before a 'grid COLS ROWS' line" : "empty: no '" MESH_MAGIC " 1' line");
    } else if (rc == 0 && vertices < (size_t)out->mesh_cols * out->mesh_rows) {
        p.line++;
        rc = fail(&p, "the file ends after %zu of the grid's %d x %d vertices", vertices, out->mesh_cols,
                  out->mesh_rows);
    }
    if (rc)
        warp_map_free(out);
    return rc;
}

int warp_mesh_load(const char *path, warp_map *out, char *err, size_t errlen)
{
    char why[128];
    size_t len = 0;
    /* 1024 x 1024 vertices of five numbers: about 40 MB */
    char *text = textfile_read_max(path, (size_t)64 << 20, &len, why, sizeof why);
    if (!text) {
        memset(out, 0, sizeof *out);
        snprintf(err, errlen, "warp mesh %s: %s", path, why);
        return -1;
    }
    int rc = warp_mesh_parse(text, len, path, out, err, errlen);
    free(text);
    return rc;
}
