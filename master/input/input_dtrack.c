/* input_dtrack: ART DTrack2 ASCII parser and UDP source. */
#include "input_dtrack.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <arpa/inet.h>
#include <ifaddrs.h>
#include <netdb.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include "base/clock.h"

/* Bounds that keep a hostile datagram from costing more than a linear scan. */
enum { MAX_TOKEN = 63, MAX_BLOCK_VALUES = 4096, MAX_BUTTONS_DECLARED = 1024,
       MAX_CONTROLLERS_DECLARED = 64 };

typedef struct cursor {
    const char *p, *end;
} cursor;

static int is_space(char ch) { return ch == ' ' || ch == '\t' || ch == '\r'; }
static int is_sep(char ch) { return is_space(ch) || ch == '[' || ch == ']'; }

static void skip_space(cursor *c)
{
    while (c->p < c->end && is_space(*c->p))
        c->p++;
}

/* The next whitespace/bracket-delimited word as a finite double. */
static int read_number(cursor *c, double *out)
{
    skip_space(c);
    const char *s = c->p;
    while (c->p < c->end && !is_sep(*c->p))
        c->p++;
    size_t n = (size_t)(c->p - s);
    if (n == 0 || n > MAX_TOKEN || memchr(s, '\0', n))
        return -1;
    char tmp[MAX_TOKEN + 1];
    memcpy(tmp, s, n);
    tmp[n] = '\0';
    char *e;
    double v = strtod(tmp, &e);
    /* Everything is stored as float: a value beyond float range is as bad as NaN. */
    if (*e != '\0' || !isfinite(v) || fabs(v) > FLT_MAX)
        return -1;
    *out = v;
    return 0;
}

static int read_count(cursor *c, int max, int *out)
{
    double v;
    if (read_number(c, &v) || v < 0 || v > max || v != floor(v))
        return -1;
    *out = (int)v;
    return 0;
}

/* "[v0 v1 ...]": at least min values; the first max are stored, the rest ignored. */
static int read_block(cursor *c, double *vals, int min, int max)
{
    skip_space(c);
    if (c->p >= c->end || *c->p != '[')
        return -1;
    c->p++;
    int n = 0;
    for (;;) {
        skip_space(c);
        if (c->p >= c->end)
            return -1;
        if (*c->p == ']') {
            c->p++;
            break;
        }
        double v;
        if (n >= MAX_BLOCK_VALUES || read_number(c, &v))
            return -1;
        if (n < max)
            vals[n] = v;
        n++;
    }
    return n >= min ? n : -1;
}

static int valid_id(double v) { return v >= 0 && v <= 1e6 && v == floor(v); }

static void store_pose(const double *pos, const double *rot, float position[3], float rotation[9])
{
    for (int i = 0; i < 3; i++)
        position[i] = (float)(pos[i] * 0.001); /* DTrack sends millimetres */
    for (int i = 0; i < 9; i++)
        rotation[i] = (float)rot[i];           /* b0..b8 are already column-wise */
}

static int parse_6d(cursor *c, input_dtrack_frame *f)
{
    int n;
    if (read_count(c, INPUT_DTRACK_MAX_BODIES - f->body_count, &n))
        return -1;
    for (int i = 0; i < n; i++) {
        double head[2], pos[6], rot[9];
        if (read_block(c, head, 2, 2) < 0 || !valid_id(head[0]) ||
            read_block(c, pos, 3, 6) < 0 || read_block(c, rot, 9, 9) < 0)
            return -1;
        input_dtrack_body *b = &f->bodies[f->body_count + i];
        b->id = (int)head[0];
        b->quality = (float)head[1];
        store_pose(pos, rot, b->position, b->rotation);
    }
    f->body_count += n;
    return 0;
}

static int parse_6df2(cursor *c, input_dtrack_frame *f)
{
    int defined, n;
    if (read_count(c, 1000000, &defined) ||
        read_count(c, INPUT_DTRACK_MAX_FLYSTICKS - f->flystick_count, &n))
        return -1;
    for (int i = 0; i < n; i++) {
        double head[4], pos[3], rot[9];
        double io[(MAX_BUTTONS_DECLARED + 31) / 32 + MAX_CONTROLLERS_DECLARED];
        if (read_block(c, head, 4, 4) < 0 || !valid_id(head[0]))
            return -1;
        if (head[2] < 0 || head[2] > MAX_BUTTONS_DECLARED || head[2] != floor(head[2]) ||
            head[3] < 0 || head[3] > MAX_CONTROLLERS_DECLARED || head[3] != floor(head[3]))
            return -1;
        int nbt = (int)head[2], nct = (int)head[3];
        int nwords = (nbt + 31) / 32;
        if (read_block(c, pos, 3, 3) < 0 || read_block(c, rot, 9, 9) < 0 ||
            read_block(c, io, nwords + nct, nwords + nct) < 0)
            return -1;
        input_dtrack_flystick *s = &f->flysticks[f->flystick_count + i];
        memset(s, 0, sizeof *s);
        s->id = (int)head[0];
        s->quality = (float)head[1];
        store_pose(pos, rot, s->position, s->rotation);
        s->button_count = nbt < INPUT_DTRACK_MAX_BUTTONS ? nbt : INPUT_DTRACK_MAX_BUTTONS;
        if (nwords > 0) {
            /* Each word carries 32 buttons; we keep the first 32. */
            if (io[0] < 0 || io[0] > 4294967295.0 || io[0] != floor(io[0]))
                return -1;
            s->buttons = (uint32_t)io[0];
            if (s->button_count < 32)
                s->buttons &= (1u << s->button_count) - 1u;
        }
        s->controller_count = nct < INPUT_DTRACK_MAX_CONTROLLERS ? nct : INPUT_DTRACK_MAX_CONTROLLERS;
        for (int k = 0; k < s->controller_count; k++)
            s->controllers[k] = (float)io[nwords + k];
    }
    f->flystick_count += n;
    return 0;
}

static int parse_3d(cursor *c, input_dtrack_frame *f)
{
    int n;
    if (read_count(c, INPUT_DTRACK_MAX_MARKERS - f->marker_count, &n))
        return -1;
    for (int i = 0; i < n; i++) {
        double head[2], pos[3];
        if (read_block(c, head, 2, 2) < 0 || !valid_id(head[0]) || read_block(c, pos, 3, 3) < 0)
            return -1;
        input_dtrack_marker *m = &f->markers[f->marker_count + i];
        m->id = (int)head[0];
        m->quality = (float)head[1];
        for (int k = 0; k < 3; k++)
            m->position[k] = (float)(pos[k] * 0.001);
    }
    f->marker_count += n;
    return 0;
}

/* Returns 1 parsed, 0 ignored, -1 bad. A bad line leaves the counts untouched. */
static int parse_line(cursor *c, input_dtrack_frame *f)
{
    skip_space(c);
    const char *w = c->p;
    while (c->p < c->end && !is_sep(*c->p))
        c->p++;
    size_t n = (size_t)(c->p - w);
    double v;
#define IS(s) (n == sizeof(s) - 1 && memcmp(w, s, n) == 0)
    if (IS("fr")) {
        if (read_number(c, &v) || v < 0 || v > 4294967295.0 || v != floor(v))
            return -1;
        f->has_frame = 1;
        f->frame = (uint32_t)v;
        return 1;
    }
    if (IS("ts")) {
        if (read_number(c, &v) || v < 0)
            return -1;
        f->has_timestamp = 1;
        f->timestamp = v;
        return 1;
    }
    if (IS("6dcal")) {
        int k;
        if (read_count(c, 1000000, &k))
            return -1;
        f->calibrated_bodies = k;
        return 1;
    }
    if (IS("6d"))
        return parse_6d(c, f) ? -1 : 1;
    if (IS("6df2"))
        return parse_6df2(c, f) ? -1 : 1;
    if (IS("3d"))
        return parse_3d(c, f) ? -1 : 1;
#undef IS
    return 0;
}

int input_dtrack_parse(const char *buf, size_t len, input_dtrack_frame *out)
{
    memset(out, 0, sizeof *out);
    out->calibrated_bodies = -1;
    const char *p = buf, *end = buf + len;
    while (p < end) {
        const char *le = memchr(p, '\n', (size_t)(end - p));
        if (!le)
            le = end;
        cursor c = {p, le};
        int r = parse_line(&c, out);
        if (r > 0)
            out->lines_parsed++;
        else if (r == 0)
            out->lines_ignored++;
        else
            out->lines_bad++;
        p = le + 1;
    }
    return out->lines_bad;
}

static void set_pose(input_pose *p, const float pos[3], const float rot[9], double t)
{
    memcpy(p->position, pos, sizeof p->position);
    memcpy(p->rotation, rot, sizeof p->rotation);
    p->valid = 1;
    p->time = t;
}

void input_dtrack_apply(const input_dtrack_desc *desc, const input_dtrack_frame *f,
                        input_source_state *st, double t)
{
    for (int i = 0; i < f->body_count; i++) {
        const input_dtrack_body *b = &f->bodies[i];
        if (b->quality < 0)
            continue;
        if (b->id == desc->head_id)
            set_pose(&st->head, b->position, b->rotation, t);
        if (desc->wand_kind == INPUT_DTRACK_WAND_BODY && b->id == desc->wand_id)
            set_pose(&st->wand, b->position, b->rotation, t);
    }
    if (desc->wand_kind != INPUT_DTRACK_WAND_FLYSTICK)
        return;
    for (int i = 0; i < f->flystick_count; i++) {
        const input_dtrack_flystick *s = &f->flysticks[i];
        if (s->id != desc->wand_id)
            continue;
        if (s->quality >= 0)
            set_pose(&st->wand, s->position, s->rotation, t);
        /* Buttons and controllers are valid even when the flystick is not seen. */
        input_source_set_buttons(st, input_map_buttons(&desc->buttons, s->buttons), t);
        if (s->controller_count > 0) {
            float axes[INPUT_AXIS_COUNT];
            input_map_axes(&desc->axes, s->controllers, s->controller_count, axes);
            input_source_set_axes(st, axes, INPUT_AXIS_COUNT, t);
        }
    }
}

typedef struct dtrack_source {
    input_source base;
    input_dtrack_desc desc;
    int fd;
    int port;
    char where[96];              /* "UDP port 5000" or "UDP 10.0.0.2:5000", for messages */
    int filtered;                /* only datagrams from `sender` count */
    struct in_addr sender;
    char sender_text[64];
    double last_datagram;        /* input clock */
    uint64_t datagrams, refused;
    ratelog refused_log;
    input_dtrack_frame frame;
    char buf[65536];
} dtrack_source;

/* Datagrams from another host than the configured sender (the last from `from`) were
 * dropped in this poll: at most one line per poll, rate-limited. */
static int refused_line(dtrack_source *d, const struct sockaddr_in *from, char *err, size_t errlen)
{
    if (!ratelog_event(&d->refused_log, clock_now_ms(), NULL))
        return 0;
    char addr[INET_ADDRSTRLEN] = "?";
    inet_ntop(AF_INET, &from->sin_addr, addr, sizeof addr);
    snprintf(err, errlen, "input %s: datagrams from %s on %s dropped: only %s may send "
             "(\"sender\" in the input config; %llu dropped so far)", d->base.name, addr, d->where,
             d->sender_text, (unsigned long long)d->refused);
    return -1;
}

static int dtrack_poll(input_source *s, double now, char *err, size_t errlen)
{
    dtrack_source *d = (dtrack_source *)s;
    int rc = 0, got = 0, refused = 0;
    struct sockaddr_in refused_from;
    for (;;) {
        struct sockaddr_in from;
        socklen_t flen = sizeof from;
        ssize_t n = recvfrom(d->fd, d->buf, sizeof d->buf, MSG_DONTWAIT, (struct sockaddr *)&from, &flen);
        if (n < 0) {
            if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)
                break;
            char why[256];
            snprintf(why, sizeof why, "DTrack receive on %s failed: %s", d->where, strerror(errno));
            return input_source_lost(s, now, why, err, errlen);
        }
        if (d->filtered && (flen < sizeof from || from.sin_addr.s_addr != d->sender.s_addr)) {
            d->refused++;
            refused = 1;
            refused_from = from;
            continue;
        }
        got = 1;
        d->datagrams++;
        input_dtrack_parse(d->buf, (size_t)n, &d->frame);
        input_dtrack_apply(&d->desc, &d->frame, &s->st, now);
    }
    if (refused)
        rc = refused_line(d, &refused_from, err, errlen);
    char text[256];
    if (got) {
        d->last_datagram = now;
        if ((s->ups == 0 || s->outage_reported) && rc == 0) {
            snprintf(text, sizeof text, "DTrack datagrams on %s", d->where);
            rc = input_source_up(s, now, text, err, errlen);
        }
    } else if (now - d->last_datagram >= d->desc.silence_s && !s->outage_reported && rc == 0) {
        snprintf(text, sizeof text, "no DTrack datagram on %s for %.1f s: tracking stands still, "
                 "buttons released, the session goes on", d->where, now - d->last_datagram);
        rc = input_source_lost(s, now, text, err, errlen);
    }
    return rc;
}

static void dtrack_close(input_source *s)
{
    dtrack_source *d = (dtrack_source *)s;
    if (d->fd >= 0)
        close(d->fd);
    free(d);
}

/* An IPv4 address, or the first IPv4 address of the interface with that name. */
static int bind_address(const char *text, struct in_addr *out)
{
    if (inet_pton(AF_INET, text, out) == 1)
        return 0;
    struct ifaddrs *list;
    if (getifaddrs(&list) != 0)
        return -1;
    int rc = -1;
    for (struct ifaddrs *i = list; i && rc; i = i->ifa_next)
        if (i->ifa_addr && i->ifa_addr->sa_family == AF_INET && strcmp(i->ifa_name, text) == 0) {
            *out = ((const struct sockaddr_in *)i->ifa_addr)->sin_addr;
            rc = 0;
        }
    freeifaddrs(list);
    return rc;
}

static input_source *open_failed(dtrack_source *d)
{
    dtrack_close(&d->base);
    return NULL;
}

input_source *input_dtrack_open(const input_dtrack_desc *desc, char *err, size_t errlen)
{
    dtrack_source *d = input_source_alloc(sizeof *d, desc->name, "dtrack", dtrack_poll, dtrack_close);
    d->desc = *desc;
    d->desc.name = d->desc.bind = d->desc.sender = NULL; /* the caller's strings are not kept */
    if (!(d->desc.silence_s > 0))
        d->desc.silence_s = INPUT_DTRACK_SILENCE_S;
    d->fd = -1;
    struct sockaddr_in a = {.sin_family = AF_INET, .sin_port = htons((uint16_t)desc->port),
                            .sin_addr.s_addr = htonl(INADDR_ANY)};
    if (desc->bind && bind_address(desc->bind, &a.sin_addr) != 0) {
        snprintf(err, errlen, "input %s: \"bind\" %s is neither an IPv4 address nor an interface "
                 "with one (see ip -4 addr)", d->base.name, desc->bind);
        return open_failed(d);
    }
    if (desc->sender) {
        struct addrinfo hints = {.ai_family = AF_INET, .ai_socktype = SOCK_DGRAM}, *ai = NULL;
        int rc = getaddrinfo(desc->sender, NULL, &hints, &ai);
        if (rc) {
            snprintf(err, errlen, "input %s: \"sender\" %s: %s (give the DTrack controller's "
                     "IPv4 address or host name)", d->base.name, desc->sender, gai_strerror(rc));
            return open_failed(d);
        }
        d->sender = ((const struct sockaddr_in *)ai->ai_addr)->sin_addr;
        freeaddrinfo(ai);
        d->filtered = 1;
        snprintf(d->sender_text, sizeof d->sender_text, "%s", desc->sender);
    }
    d->fd = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    /* A large receive buffer so that a stalled master frame does not drop datagrams. No
     * SO_REUSEADDR: a second socket on this port (another user's) must fail to bind, not
     * share or steal the tracker's datagrams. */
    int rcvbuf = 1 << 20;
    if (d->fd < 0 || setsockopt(d->fd, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf) ||
        bind(d->fd, (struct sockaddr *)&a, sizeof a)) {
        char addr[INET_ADDRSTRLEN] = "";
        inet_ntop(AF_INET, &a.sin_addr, addr, sizeof addr);
        snprintf(err, errlen, "input %s: cannot listen for DTrack on UDP %s:%d: %s "
                 "(is another program using the port? set \"port\" or \"bind\" in the input config)",
                 d->base.name, addr, desc->port, strerror(errno));
        return open_failed(d);
    }
    socklen_t alen = sizeof a;
    getsockname(d->fd, (struct sockaddr *)&a, &alen);
    d->port = ntohs(a.sin_port);
    if (desc->bind)
        snprintf(d->where, sizeof d->where, "UDP %s:%d", desc->bind, d->port);
    else
        snprintf(d->where, sizeof d->where, "UDP port %d", d->port);
    return &d->base;
}

int input_dtrack_port(const input_source *s)
{
    return ((const dtrack_source *)s)->port;
}

uint64_t input_dtrack_datagrams(const input_source *s)
{
    return ((const dtrack_source *)s)->datagrams;
}

uint64_t input_dtrack_refused(const input_source *s)
{
    return ((const dtrack_source *)s)->refused;
}
