/* input_vrpn: VRPN client, TCP-only connection mode, with reconnection. */
#include "input_vrpn.h"

#include "base/byteorder.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <netdb.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <unistd.h>

static uint32_t be32(const uint8_t *p) { return (uint32_t)be_get(p, 4); }
static void put32(uint8_t *p, uint32_t v) { be_put(p, v, 4); }

static double bef64(const uint8_t *p)
{
    uint64_t u = be_get(p, 8);
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

void input_vrpn_write_cookie(uint8_t cookie[INPUT_VRPN_COOKIE_SIZE])
{
    memset(cookie, 0, INPUT_VRPN_COOKIE_SIZE);
    /* magic, two spaces, remote logging mode '0' (none) */
    snprintf((char *)cookie, INPUT_VRPN_COOKIE_SIZE, "%s  0", INPUT_VRPN_COOKIE);
}

int input_vrpn_cookie_ok(const uint8_t cookie[INPUT_VRPN_COOKIE_SIZE])
{
    /* "vrpn: ver. 07.": only the major version has to match. */
    size_t major = strlen(INPUT_VRPN_COOKIE) - 2;
    return memcmp(cookie, INPUT_VRPN_COOKIE, major) == 0;
}

size_t input_vrpn_frame(uint8_t *out, size_t cap, int32_t sender, int32_t type,
                        const void *body, size_t body_len)
{
    size_t len = INPUT_VRPN_HEADER_SIZE + body_len, padded = (len + 7) & ~(size_t)7;
    if (padded > cap || len > INPUT_VRPN_MAX_MESSAGE)
        return 0;
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    memset(out, 0, padded);
    put32(out, (uint32_t)len);
    put32(out + 4, (uint32_t)ts.tv_sec);
    put32(out + 8, (uint32_t)(ts.tv_nsec / 1000));
    put32(out + 12, (uint32_t)sender);
    put32(out + 16, (uint32_t)type);
    if (body_len)
        memcpy(out + INPUT_VRPN_HEADER_SIZE, body, body_len);
    return padded;
}

/* ---- decoding ---- */

static const char *tracker_name(const input_vrpn_desc *d) { return d->tracker ? d->tracker : "Tracker0"; }
static const char *buttons_name(const input_vrpn_desc *d) { return d->buttons ? d->buttons : tracker_name(d); }
static const char *analog_name(const input_vrpn_desc *d) { return d->analog ? d->analog : buttons_name(d); }

static int describe(char table[][64], int32_t id, const uint8_t *body, size_t blen)
{
    if (id < 0 || id >= INPUT_VRPN_MAX_IDS || blen < 4)
        return -1;
    uint32_t n = be32(body);
    if (n < 1 || n > blen - 4)
        return -1;
    const char *name = (const char *)body + 4;
    size_t sl = strnlen(name, n);
    if (sl == 0 || sl > 63)
        return -1;
    memcpy(table[id], name, sl);
    table[id][sl] = '\0';
    return 0;
}

static int pos_quat(const input_vrpn_desc *d, const uint8_t *b, size_t blen,
                    input_source_state *st, double t)
{
    if (blen < 64)
        return -1;
    int32_t sensor = (int32_t)be32(b);
    double v[7];
    for (int i = 0; i < 7; i++) {
        v[i] = bef64(b + 8 + 8 * i);
        if (!isfinite(v[i]) || fabs(v[i]) > FLT_MAX)
            return -1;
    }
    double x = v[3], y = v[4], z = v[5], w = v[6];
    double n = sqrt(x * x + y * y + z * z + w * w);
    if (n < 1e-6)
        return -1;
    x /= n, y /= n, z /= n, w /= n;
    int head = d->sensors_set ? d->head_sensor : 0, wand = d->sensors_set ? d->wand_sensor : 1;
    input_pose *p = sensor == head ? &st->head : sensor == wand ? &st->wand : NULL;
    if (!p)
        return 0;
    const double r[9] = {/* column-major rotation of the unit quaternion (x, y, z, w) */
        1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w),
        2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
        2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)};
    for (int i = 0; i < 3; i++)
        p->position[i] = (float)v[i];
    for (int i = 0; i < 9; i++)
        p->rotation[i] = (float)r[i];
    p->valid = 1;
    p->time = t;
    return 0;
}

static void set_raw_button(input_vrpn_session *s, int32_t b, int32_t state)
{
    if (b < 0 || b >= 32)
        return;
    if (state)
        s->raw_buttons |= 1u << b;
    else
        s->raw_buttons &= ~(1u << b);
}

static int button_change(input_vrpn_session *s, const uint8_t *b, size_t blen)
{
    if (blen == 8) {
        set_raw_button(s, (int32_t)be32(b), (int32_t)be32(b + 4));
        return 0;
    }
    /* Some servers batch changes: a count, then (button, state) pairs. */
    if (blen < 4)
        return -1;
    uint32_t n = be32(b);
    if (n > 256 || blen < 4 + 8 * (size_t)n)
        return -1;
    for (uint32_t i = 0; i < n; i++)
        set_raw_button(s, (int32_t)be32(b + 4 + 8 * i), (int32_t)be32(b + 8 + 8 * i));
    return 0;
}

static int button_states(input_vrpn_session *s, const uint8_t *b, size_t blen)
{
    if (blen < 4)
        return -1;
    uint32_t n = be32(b);
    if (n > 256 || blen < 4 + 4 * (size_t)n)
        return -1;
    s->raw_buttons = 0;
    for (uint32_t i = 0; i < n; i++)
        set_raw_button(s, (int32_t)i, (int32_t)be32(b + 4 + 4 * i));
    return 0;
}

static int analog_channel(const input_vrpn_desc *d, const uint8_t *b, size_t blen,
                          input_source_state *st, double t)
{
    if (blen < 8)
        return -1;
    double n = bef64(b);
    if (!(n >= 0 && n <= 128) || n != floor(n) || blen < 8 + 8 * (size_t)n)
        return -1;
    float ch[INPUT_MAP_SIZE];
    int count = (int)n < INPUT_MAP_SIZE ? (int)n : INPUT_MAP_SIZE;
    for (int i = 0; i < count; i++) {
        double v = bef64(b + 8 + 8 * i);
        if (!isfinite(v))
            return -1;
        ch[i] = (float)(v < -1 ? -1 : v > 1 ? 1 : v);
    }
    float axes[INPUT_AXIS_COUNT];
    input_map_axes(&d->axis_map, ch, count, axes);
    input_source_set_axes(st, axes, INPUT_AXIS_COUNT, t);
    return 0;
}

long input_vrpn_decode(const input_vrpn_desc *desc, input_vrpn_session *s, const uint8_t *buf,
                       size_t len, input_source_state *st, double t, char *err, size_t errlen)
{
    size_t off = 0;
    while (len - off >= INPUT_VRPN_HEADER_SIZE) {
        const uint8_t *h = buf + off;
        uint32_t mlen = be32(h);
        if (mlen < INPUT_VRPN_HEADER_SIZE || mlen > INPUT_VRPN_MAX_MESSAGE) {
            snprintf(err, errlen, "message length %u outside [%d, %d]: not a VRPN stream",
                     mlen, INPUT_VRPN_HEADER_SIZE, INPUT_VRPN_MAX_MESSAGE);
            return -1;
        }
        size_t padded = ((size_t)mlen + 7) & ~(size_t)7;
        if (len - off < padded)
            break;
        int32_t sender = (int32_t)be32(h + 12), type = (int32_t)be32(h + 16);
        const uint8_t *body = h + INPUT_VRPN_HEADER_SIZE;
        size_t blen = mlen - INPUT_VRPN_HEADER_SIZE;
        off += padded;
        int bad = 0;
        if (type == INPUT_VRPN_SENDER_DESCRIPTION) {
            bad = describe(s->senders, sender, body, blen);
        } else if (type == INPUT_VRPN_TYPE_DESCRIPTION) {
            bad = describe(s->types, sender, body, blen);
        } else if (type < 0) {
            continue; /* other system messages (UDP, log, disconnect) do not concern us */
        } else if (type >= INPUT_VRPN_MAX_IDS || sender < 0 || sender >= INPUT_VRPN_MAX_IDS ||
                   !s->types[type][0] || !s->senders[sender][0]) {
            bad = 1;
        } else {
            const char *tn = s->types[type], *sn = s->senders[sender];
            uint32_t before = s->raw_buttons;
            int known = 1;
            if (strcmp(tn, "vrpn_Tracker Pos_Quat") == 0 && strcmp(sn, tracker_name(desc)) == 0)
                bad = pos_quat(desc, body, blen, st, t);
            else if (strcmp(tn, "vrpn_Button Change") == 0 && strcmp(sn, buttons_name(desc)) == 0)
                bad = button_change(s, body, blen);
            else if (strcmp(tn, "vrpn_Button States") == 0 && strcmp(sn, buttons_name(desc)) == 0)
                bad = button_states(s, body, blen);
            else if (strcmp(tn, "vrpn_Analog Channel") == 0 && strcmp(sn, analog_name(desc)) == 0)
                bad = analog_channel(desc, body, blen, st, t);
            else
                known = 0;
            if (s->raw_buttons != before)
                input_source_set_buttons(st, input_map_buttons(&desc->button_map, s->raw_buttons), t);
            if (known && !bad)
                s->messages++;
        }
        if (bad)
            s->dropped++;
    }
    return (long)off;
}

/* ---- the TCP source ---- */

typedef enum vrpn_state { VRPN_IDLE, VRPN_CONNECTING, VRPN_COOKIE, VRPN_OPEN } vrpn_state;

typedef struct vrpn_source {
    input_source base;
    input_vrpn_desc desc;
    char host[256], tracker[64], buttons[64], analog[64];
    int fd;
    vrpn_state state;
    int connections;
    input_vrpn_session session;
    uint8_t out[4096];
    size_t out_len, out_off;
    size_t in_len;
    uint8_t in[2 * INPUT_VRPN_MAX_MESSAGE];
} vrpn_source;

static void queue_description(vrpn_source *v, int32_t id, int32_t kind, const char *name)
{
    uint8_t body[80];
    size_t n = strlen(name) + 1;
    put32(body, (uint32_t)n);
    memcpy(body + 4, name, n);
    v->out_len += input_vrpn_frame(v->out + v->out_len, sizeof v->out - v->out_len, id, kind,
                                   body, 4 + n);
}

/* Closes the connection and starts an outage (input_source_lost()). */
static int fail(vrpn_source *v, double now, char *err, size_t errlen, const char *what)
{
    if (v->fd >= 0)
        close(v->fd);
    v->fd = -1;
    v->state = VRPN_IDLE;
    memset(&v->session, 0, sizeof v->session);
    v->in_len = v->out_len = v->out_off = 0;
    char why[sizeof v->host + 384]; /* host, port and a reason of up to 300 bytes */
    snprintf(why, sizeof why, "VRPN server %s:%d: %s", v->host, v->desc.port, what);
    return input_source_lost(&v->base, now, why, err, errlen);
}

static int start_connect(vrpn_source *v, double now, char *err, size_t errlen)
{
    char port[16], why[300];
    snprintf(port, sizeof port, "%d", v->desc.port);
    struct addrinfo hints = {.ai_family = AF_UNSPEC, .ai_socktype = SOCK_STREAM}, *ai = NULL;
    int rc = getaddrinfo(v->host, port, &hints, &ai);
    if (rc) {
        snprintf(why, sizeof why, "cannot resolve host: %s", gai_strerror(rc));
        return fail(v, now, err, errlen, why);
    }
    v->fd = socket(ai->ai_family, SOCK_STREAM, 0);
    if (v->fd < 0) {
        freeaddrinfo(ai);
        return fail(v, now, err, errlen, strerror(errno));
    }
    fcntl(v->fd, F_SETFL, fcntl(v->fd, F_GETFL) | O_NONBLOCK);
    int one = 1;
    setsockopt(v->fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one); /* tracker latency */
    rc = connect(v->fd, ai->ai_addr, ai->ai_addrlen);
    freeaddrinfo(ai);
    if (rc && errno != EINPROGRESS) {
        snprintf(why, sizeof why, "cannot connect: %s", strerror(errno));
        return fail(v, now, err, errlen, why);
    }
    v->state = VRPN_CONNECTING;
    /* Our cookie, then descriptions of the names we use (ids are ours, per connection). */
    input_vrpn_write_cookie(v->out);
    v->out_len = INPUT_VRPN_COOKIE_SIZE;
    v->out_off = 0;
    const char *senders[3] = {v->tracker, v->buttons, v->analog};
    for (int i = 0; i < 3; i++)
        queue_description(v, i, INPUT_VRPN_SENDER_DESCRIPTION, senders[i]);
    const char *types[4] = {"vrpn_Tracker Pos_Quat", "vrpn_Button Change", "vrpn_Button States",
                            "vrpn_Analog Channel"};
    for (int i = 0; i < 4; i++)
        queue_description(v, i, INPUT_VRPN_TYPE_DESCRIPTION, types[i]);
    return 0;
}

static int vrpn_poll(input_source *s, double now, char *err, size_t errlen)
{
    vrpn_source *v = (vrpn_source *)s;
    char why[300];
    int said = 0; /* a notice (connected) is in err */
    if (v->state == VRPN_IDLE) {
        if (!input_source_retry_due(s, now))
            return 0;
        if (start_connect(v, now, err, errlen))
            return -1;
        if (v->state == VRPN_IDLE)
            return 0;
    }
    if (v->state == VRPN_CONNECTING) {
        struct pollfd pfd = {.fd = v->fd, .events = POLLOUT};
        if (poll(&pfd, 1, 0) <= 0)
            return 0;
        int soerr = 0;
        socklen_t sl = sizeof soerr;
        getsockopt(v->fd, SOL_SOCKET, SO_ERROR, &soerr, &sl);
        if (soerr) {
            snprintf(why, sizeof why, "cannot connect: %s", strerror(soerr));
            return fail(v, now, err, errlen, why);
        }
        v->state = VRPN_COOKIE;
    }
    while (v->out_off < v->out_len) {
        ssize_t n = send(v->fd, v->out + v->out_off, v->out_len - v->out_off, MSG_NOSIGNAL);
        if (n < 0) {
            if (errno == EAGAIN || errno == EWOULDBLOCK)
                break;
            snprintf(why, sizeof why, "send failed: %s", strerror(errno));
            return fail(v, now, err, errlen, why);
        }
        v->out_off += (size_t)n;
    }
    for (;;) {
        if (v->in_len == sizeof v->in)
            return fail(v, now, err, errlen, "receive buffer overrun");
        ssize_t n = recv(v->fd, v->in + v->in_len, sizeof v->in - v->in_len, MSG_DONTWAIT);
        if (n == 0)
            return fail(v, now, err, errlen, "connection closed by the server");
        if (n < 0) {
            if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)
                break;
            snprintf(why, sizeof why, "receive failed: %s", strerror(errno));
            return fail(v, now, err, errlen, why);
        }
        v->in_len += (size_t)n;
        size_t used = 0;
        if (v->state == VRPN_COOKIE) {
            if (v->in_len < INPUT_VRPN_COOKIE_SIZE)
                continue;
            if (!input_vrpn_cookie_ok(v->in))
                return fail(v, now, err, errlen, "bad cookie, not a VRPN 07 server");
            v->state = VRPN_OPEN;
            v->connections++;
            char what[sizeof v->host + 128];
            snprintf(what, sizeof what, "connected to VRPN server %s:%d (%s)", v->host, v->desc.port,
                     v->tracker);
            said = input_source_up(s, now, what, err, errlen);
            used = INPUT_VRPN_COOKIE_SIZE;
        }
        long c = input_vrpn_decode(&v->desc, &v->session, v->in + used, v->in_len - used,
                                   &s->st, now, why, sizeof why);
        if (c < 0)
            return fail(v, now, err, errlen, why);
        used += (size_t)c;
        memmove(v->in, v->in + used, v->in_len - used);
        v->in_len -= used;
    }
    return said;
}

static void vrpn_close(input_source *s)
{
    vrpn_source *v = (vrpn_source *)s;
    if (v->fd >= 0)
        close(v->fd);
    free(v);
}

input_source *input_vrpn_open(const input_vrpn_desc *desc, char *err, size_t errlen)
{
    vrpn_source *v = input_source_alloc(sizeof *v, desc->name, "vrpn", vrpn_poll, vrpn_close);
    v->desc = *desc;
    snprintf(v->host, sizeof v->host, "%s", desc->host ? desc->host : "localhost");
    snprintf(v->tracker, sizeof v->tracker, "%s", tracker_name(desc));
    snprintf(v->buttons, sizeof v->buttons, "%s", buttons_name(desc));
    snprintf(v->analog, sizeof v->analog, "%s", analog_name(desc));
    v->desc.name = NULL;
    v->desc.host = v->host;
    v->desc.tracker = v->tracker;
    v->desc.buttons = v->buttons;
    v->desc.analog = v->analog;
    if (v->desc.port <= 0)
        v->desc.port = INPUT_VRPN_DEFAULT_PORT;
    if (v->desc.reconnect_interval <= 0)
        v->desc.reconnect_interval = INPUT_SOURCE_RETRY_INTERVAL;
    v->base.retry_interval = v->desc.reconnect_interval;
    v->fd = -1;
    return &v->base;
}

int input_vrpn_connected(const input_source *s)
{
    return ((const vrpn_source *)s)->state == VRPN_OPEN;
}

int input_vrpn_connections(const input_source *s)
{
    return ((const vrpn_source *)s)->connections;
}
