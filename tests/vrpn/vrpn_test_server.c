/* vrpn_test_server: a small VRPN server for tests, written from the public protocol
 * description (not from VRPN's code, and sharing no code with master/input/input_vrpn.c).
 *
 *   vrpn_test_server [--port N] [--x X] [--seconds S] [--bad-cookie] [--oversized]
 *
 * Listens on TCP port N (0 = any; the chosen port is printed as "port N" on stdout),
 * accepts one client at a time, exchanges cookies and then, every 10 ms, sends as device
 * "Tracker0": Pos_Quat for sensor 0 (head at (X, 1.7, 0), identity) and sensor 1 (wand at
 * (X + 0.3, 1.2, -0.4), turned 90 degrees about Y); as "Wand0": Button States (4 buttons)
 * once, then Button Change toggling button 2 every 10 frames, and Analog Channel (0.5,
 * -0.25). Sender and type ids are deliberately not 0, 1, 2... so that the client must use
 * the descriptions. --bad-cookie answers with a wrong cookie; --oversized sends one message
 * whose length field is 1 MiB. Exits after S seconds (default 30) or on SIGTERM. */
#define _POSIX_C_SOURCE 200809L
#include <arpa/inet.h>
#include <errno.h>
#include <math.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

enum { SENDER_TRACKER = 3, SENDER_WAND = 5, TYPE_POS_QUAT = 7, TYPE_CHANGE = 2,
       TYPE_STATES = 4, TYPE_ANALOG = 9 };

static volatile sig_atomic_t stop;
static void on_term(int sig) { (void)sig; stop = 1; }

static void be32(uint8_t *p, uint32_t v)
{
    uint32_t n = htonl(v);
    memcpy(p, &n, 4);
}

static void bef64(uint8_t *p, double d)
{
    uint64_t u;
    memcpy(&u, &d, 8);
    be32(p, (uint32_t)(u >> 32));
    be32(p + 4, (uint32_t)u);
}

static int send_all(int fd, const uint8_t *b, size_t n)
{
    while (n) {
        ssize_t k = send(fd, b, n, MSG_NOSIGNAL);
        if (k <= 0)
            return -1;
        b += k;
        n -= (size_t)k;
    }
    return 0;
}

/* Header: length (24 + body), seconds, microseconds, sender, type, 4 bytes padding;
 * the body is padded to 8 bytes. */
static int send_msg(int fd, int32_t sender, int32_t type, const uint8_t *body, size_t blen,
                    uint32_t length_field)
{
    uint8_t m[1024] = {0};
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    be32(m, length_field ? length_field : (uint32_t)(24 + blen));
    be32(m + 4, (uint32_t)ts.tv_sec);
    be32(m + 8, (uint32_t)(ts.tv_nsec / 1000));
    be32(m + 12, (uint32_t)sender);
    be32(m + 16, (uint32_t)type);
    memcpy(m + 24, body, blen);
    return send_all(fd, m, (24 + blen + 7) & ~(size_t)7);
}

static int describe(int fd, int32_t id, int32_t kind, const char *name)
{
    uint8_t b[128];
    size_t n = strlen(name) + 1;
    be32(b, (uint32_t)n);
    memcpy(b + 4, name, n);
    return send_msg(fd, id, kind, b, 4 + n, 0);
}

static int pos_quat(int fd, int sensor, double x, double y, double z, const double q[4])
{
    uint8_t b[64] = {0};
    be32(b, (uint32_t)sensor);
    const double v[7] = {x, y, z, q[0], q[1], q[2], q[3]};
    for (int i = 0; i < 7; i++)
        bef64(b + 8 + 8 * i, v[i]);
    return send_msg(fd, SENDER_TRACKER, TYPE_POS_QUAT, b, sizeof b, 0);
}

static int serve(int fd, double x, int bad_cookie, int oversized, double deadline)
{
    uint8_t cookie[24] = {0}, theirs[24];
    snprintf((char *)cookie, sizeof cookie, "%s  0", bad_cookie ? "nope: ver. 99.99" : "vrpn: ver. 07.35");
    size_t got = 0;
    while (got < 24) { /* the client speaks first in TCP-only mode */
        ssize_t k = recv(fd, theirs + got, 24 - got, 0);
        if (k <= 0)
            return -1;
        got += (size_t)k;
    }
    if (memcmp(theirs, "vrpn: ver. 07.", 14) != 0) {
        fprintf(stderr, "vrpn_test_server: client cookie is not VRPN 07\n");
        return -1;
    }
    if (send_all(fd, cookie, sizeof cookie))
        return -1;
    if (describe(fd, SENDER_TRACKER, -1, "Tracker0") || describe(fd, SENDER_WAND, -1, "Wand0") ||
        describe(fd, TYPE_POS_QUAT, -2, "vrpn_Tracker Pos_Quat") ||
        describe(fd, TYPE_CHANGE, -2, "vrpn_Button Change") ||
        describe(fd, TYPE_STATES, -2, "vrpn_Button States") ||
        describe(fd, TYPE_ANALOG, -2, "vrpn_Analog Channel"))
        return -1;
    uint8_t states[20];
    be32(states, 4);
    for (int i = 0; i < 4; i++)
        be32(states + 4 + 4 * i, i == 0);
    if (send_msg(fd, SENDER_WAND, TYPE_STATES, states, sizeof states, 0))
        return -1;
    if (oversized) {
        uint8_t z[8] = {0};
        send_msg(fd, SENDER_WAND, TYPE_STATES, z, sizeof z, 1u << 20);
    }
    const double ident[4] = {0, 0, 0, 1}, turned[4] = {0, sin(0.78539816339744831), 0, cos(0.78539816339744831)};
    for (int frame = 0; !stop; frame++) {
        struct timespec now;
        clock_gettime(CLOCK_MONOTONIC, &now);
        if (now.tv_sec + 1e-9 * now.tv_nsec > deadline)
            return 1;
        if (pos_quat(fd, 0, x, 1.7, 0.0, ident) || pos_quat(fd, 1, x + 0.3, 1.2, -0.4, turned))
            return -1;
        if (frame % 10 == 0) {
            uint8_t c[8];
            be32(c, 2);
            be32(c + 4, (uint32_t)((frame / 10) & 1));
            if (send_msg(fd, SENDER_WAND, TYPE_CHANGE, c, sizeof c, 0))
                return -1;
        }
        uint8_t a[24];
        bef64(a, 2.0);
        bef64(a + 8, 0.5);
        bef64(a + 16, -0.25);
        if (send_msg(fd, SENDER_WAND, TYPE_ANALOG, a, sizeof a, 0))
            return -1;
        /* Read and ignore what the client sends (its descriptions); notice it leaving. */
        struct pollfd p = {.fd = fd, .events = POLLIN};
        if (poll(&p, 1, 10) > 0) {
            uint8_t junk[4096];
            if (recv(fd, junk, sizeof junk, 0) <= 0)
                return -1;
        }
    }
    return 1;
}

int main(int argc, char **argv)
{
    int port = 0, bad_cookie = 0, oversized = 0;
    double x = 0.0, seconds = 30.0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--port") == 0 && i + 1 < argc) port = atoi(argv[++i]);
        else if (strcmp(argv[i], "--x") == 0 && i + 1 < argc) x = atof(argv[++i]);
        else if (strcmp(argv[i], "--seconds") == 0 && i + 1 < argc) seconds = atof(argv[++i]);
        else if (strcmp(argv[i], "--bad-cookie") == 0) bad_cookie = 1;
        else if (strcmp(argv[i], "--oversized") == 0) oversized = 1;
        else {
            fprintf(stderr, "usage: vrpn_test_server [--port N] [--x X] [--seconds S] "
                            "[--bad-cookie] [--oversized]\n");
            return 2;
        }
    }
    struct sigaction sa = {.sa_handler = on_term};
    sigaction(SIGTERM, &sa, NULL);
    int ls = socket(AF_INET, SOCK_STREAM, 0), one = 1;
    setsockopt(ls, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    struct sockaddr_in a = {.sin_family = AF_INET, .sin_port = htons((uint16_t)port),
                            .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    socklen_t al = sizeof a;
    if (bind(ls, (struct sockaddr *)&a, sizeof a) || listen(ls, 4) ||
        getsockname(ls, (struct sockaddr *)&a, &al)) {
        fprintf(stderr, "vrpn_test_server: cannot listen on port %d: %s\n", port, strerror(errno));
        return 1;
    }
    printf("port %d\n", ntohs(a.sin_port));
    fflush(stdout);
    struct timespec t0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    double deadline = t0.tv_sec + 1e-9 * t0.tv_nsec + seconds;
    while (!stop) {
        struct pollfd p = {.fd = ls, .events = POLLIN};
        if (poll(&p, 1, 100) <= 0)
            continue;
        int fd = accept(ls, NULL, NULL);
        if (fd < 0)
            continue;
        int r = serve(fd, x, bad_cookie, oversized, deadline);
        close(fd);
        if (r > 0)
            break;
        struct timespec now;
        clock_gettime(CLOCK_MONOTONIC, &now);
        if (now.tv_sec + 1e-9 * now.tv_nsec > deadline)
            break;
    }
    close(ls);
    return 0;
}
