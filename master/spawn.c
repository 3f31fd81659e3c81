#include "spawn.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

/* The longest line the relay names as one (longer ones go on in pieces). */
enum { RELAY_LINE = 4096 };

/* One line (or a piece of a long one) of a child's output for the master's output, naming
 * its node when the line does not: "cavelight-node: x" (a warning from deep inside the
 * renderer) becomes "cavelight-node NODE: x", any other line "NODE| x" (the prefix of
 * spawn_log_tail()'s lines). One write per line, so relays of several nodes never mix
 * inside a line. */
static void relay_line(const char *label, const char *s, size_t len, int line_start)
{
    static const char prog[] = "cavelight-node";
    size_t plen = sizeof prog - 1, llen = strlen(label);
    char out[RELAY_LINE + 160];
    int head = 0;
    size_t skip = 0;
    if (line_start && len > plen && memcmp(s, prog, plen) == 0 && s[plen] == ':') {
        head = snprintf(out, 160, "%s %s", prog, label);
        skip = plen;
    } else if (line_start && !(len > plen + llen && memcmp(s, prog, plen) == 0 && s[plen] == ' ' &&
                               memcmp(s + plen + 1, label, llen) == 0)) {
        head = snprintf(out, 160, "%s| ", label);
    }
    memcpy(out + head, s + skip, len - skip);
    if (write(STDERR_FILENO, out, (size_t)head + len - skip) < 0) {
        /* a closed terminal: keep draining so the child never blocks */
    }
}

/* The log relay: copies what a child writes to its log file as it is and, line by line
 * with its node named (relay_line()), to the master's standard error, until every writer
 * has closed the pipe. It holds nothing else of the master's (its sockets would outlive the
 * master otherwise), and leaves the stopping to the child. */
static void relay(const char *label, int in, int log_fd)
{
    signal(SIGINT, SIG_IGN);
    signal(SIGTERM, SIG_IGN);
    long max_fd = sysconf(_SC_OPEN_MAX);
    for (int fd = 3; fd < (max_fd > 0 && max_fd < 65536 ? max_fd : 65536); fd++)
        if (fd != in && fd != log_fd)
            close(fd);
    char buf[RELAY_LINE];
    size_t held = 0;    /* the start of a line not yet ended */
    int line_start = 1; /* held starts a line (not the rest of a long one) */
    for (;;) {
        ssize_t n = read(in, buf + held, sizeof buf - held);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            if (held)
                relay_line(label, buf, held, line_start);
            _exit(0);
        }
        if (write(log_fd, buf + held, (size_t)n) < 0) {
            /* a full disk: keep draining so the child never blocks */
        }
        held += (size_t)n;
        size_t done = 0;
        for (char *nl; (nl = memchr(buf + done, '\n', held - done)) != NULL; line_start = 1) {
            size_t len = (size_t)(nl - (buf + done)) + 1;
            relay_line(label, buf + done, len, line_start);
            done += len;
        }
        if (done == 0 && held == sizeof buf) { /* a line longer than the buffer: its first part */
            relay_line(label, buf, held, line_start);
            line_start = 0;
            done = held;
        }
        memmove(buf, buf + done, held - done);
        held -= done;
    }
}

/* Starts the relay for log_path; returns the pipe's write end for the child, or -1. */
static int start_relay(spawn_set *s, int i, const char *log_path, char *err, size_t errlen)
{
    int log_fd = open(log_path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644), fds[2];
    if (log_fd < 0) {
        snprintf(err, errlen, "spawn %s: cannot create its log %s: %s", s->label[i], log_path, strerror(errno));
        return -1;
    }
    if (pipe(fds) != 0) {
        snprintf(err, errlen, "spawn %s: pipe for its log: %s", s->label[i], strerror(errno));
        close(log_fd);
        return -1;
    }
    s->relay[i] = fork();
    if (s->relay[i] == 0) {
        close(fds[1]);
        relay(s->label[i], fds[0], log_fd);
    }
    close(fds[0]);
    close(log_fd);
    if (s->relay[i] < 0) {
        snprintf(err, errlen, "spawn %s: fork for its log failed: %s", s->label[i], strerror(errno));
        close(fds[1]);
        return -1;
    }
    return fds[1];
}

static int start(spawn_set *s, const char *label, const char *path, char *const argv[],
                 const char *workdir, const char *log_path, char *err, size_t errlen)
{
    if (s->count >= SPAWN_MAX) {
        snprintf(err, errlen, "spawn %s: more than %d children", label, SPAWN_MAX);
        return -1;
    }
    int i = s->count;
    snprintf(s->label[i], sizeof s->label[i], "%s", label);
    snprintf(s->log[i], sizeof s->log[i], "%s", log_path ? log_path : "");
    s->relay[i] = 0;
    int log_fd = log_path ? start_relay(s, i, log_path, err, errlen) : -1;
    if (log_path && log_fd < 0)
        return -1;
    pid_t parent = getpid();
    pid_t pid = fork();
    if (pid < 0) {
        snprintf(err, errlen, "spawn %s: fork failed: %s", label, strerror(errno));
        if (log_fd >= 0)
            close(log_fd); /* the relay sees the end of its pipe and leaves */
        return -1;
    }
    if (pid == 0) {
        /* Die with the master, even if it is killed without a chance to clean up. */
        prctl(PR_SET_PDEATHSIG, SIGTERM);
        if (getppid() != parent)
            _exit(127);
        /* Own process group: stopping the child also stops what a launch shell started. */
        setpgid(0, 0);
        if (log_fd >= 0 && (dup2(log_fd, STDOUT_FILENO) < 0 || dup2(log_fd, STDERR_FILENO) < 0))
            _exit(127);
        if (log_fd >= 0)
            close(log_fd);
        if (workdir && chdir(workdir) != 0) {
            fprintf(stderr, "cavelight-master: %s: cannot enter %s: %s\n", label, workdir, strerror(errno));
            _exit(127);
        }
        execv(path, argv);
        fprintf(stderr, "cavelight-master: cannot run %s: %s\n", path, strerror(errno));
        _exit(127);
    }
    if (log_fd >= 0)
        close(log_fd);
    s->count++;
    s->pid[i] = pid;
    s->exited[i] = 0;
    s->status[i] = 0;
    return 0;
}

int spawn_find(const spawn_set *s, const char *label)
{
    for (int i = 0; i < s->count; i++)
        if (strcmp(s->label[i], label) == 0)
            return i;
    return -1;
}

/* Waits up to timeout_ms for child i's relay to copy the child's last words, then stops it. */
static void end_relay(spawn_set *s, int i, int timeout_ms)
{
    struct timespec step = {0, 10 * 1000 * 1000};
    for (int waited = 0; s->relay[i] > 0; waited += 10) {
        if (waitpid(s->relay[i], NULL, WNOHANG) == s->relay[i]) {
            s->relay[i] = 0;
        } else if (waited >= timeout_ms) {
            kill(s->relay[i], SIGKILL); /* a grandchild that left the group still holds the pipe */
            waitpid(s->relay[i], NULL, 0);
            s->relay[i] = 0;
        } else {
            nanosleep(&step, NULL);
        }
    }
}

void spawn_log_tail(spawn_set *s, int i, int lines, const char *prefix, FILE *f)
{
    enum { TAIL_BYTES = 4096 };
    if (s->exited[i])
        end_relay(s, i, 1000);
    FILE *in = s->log[i][0] ? fopen(s->log[i], "r") : NULL;
    if (!in)
        return;
    char buf[TAIL_BYTES + 1];
    fseek(in, 0, SEEK_END);
    long size = ftell(in);
    fseek(in, size > TAIL_BYTES ? size - TAIL_BYTES : 0, SEEK_SET);
    size_t n = fread(buf, 1, TAIL_BYTES, in);
    fclose(in);
    buf[n] = 0;
    while (n > 0 && buf[n - 1] == '\n')
        buf[--n] = 0;
    char *start = buf + n;
    for (int seen = 0; start > buf && seen < lines; start--)
        if (start[-1] == '\n' && ++seen == lines)
            break;
    for (char *line = start; *line;) {
        size_t len = strcspn(line, "\n");
        fprintf(f, "%s%.*s\n", prefix, (int)len, line);
        line += len + (line[len] == '\n');
    }
}

int spawn_local(spawn_set *s, const char *label, char *const argv[], const char *workdir,
                const char *log_path, char *err, size_t errlen)
{
    if (access(argv[0], X_OK) != 0) {
        snprintf(err, errlen, "spawn %s: %s is not an executable: build it, or give the node's "
                 "\"exe\" in the config or --node-exe", label, argv[0]);
        return -1;
    }
    return start(s, label, argv[0], argv, workdir, log_path, err, errlen);
}

int spawn_shell_quote(const char *s, char *out, size_t cap)
{
    size_t n = 0;
    if (cap < 3)
        return -1;
    out[n++] = '\'';
    for (; *s; s++) {
        const char *piece = *s == '\'' ? "'\\''" : NULL;
        size_t len = piece ? 4 : 1;
        if (n + len + 2 > cap)
            return -1;
        if (piece)
            memcpy(out + n, piece, 4);
        else
            out[n] = *s;
        n += len;
    }
    out[n++] = '\'';
    out[n] = 0;
    return 0;
}

int spawn_remote(spawn_set *s, const char *label, const char *tmpl, const char *host, const char *command,
                 const char *log_path, char *err, size_t errlen)
{
    char qhost[512], qcmd[4096], line[8192];
    if (spawn_shell_quote(host, qhost, sizeof qhost) || spawn_shell_quote(command, qcmd, sizeof qcmd)) {
        snprintf(err, errlen, "spawn %s: host or command too long", label);
        return -1;
    }
    size_t n = 0;
    for (const char *p = tmpl; *p;) {
        const char *rep = NULL;
        size_t skip = 1;
        if (strncmp(p, "{host}", 6) == 0) {
            rep = qhost;
            skip = 6;
        } else if (strncmp(p, "{command}", 9) == 0) {
            rep = qcmd;
            skip = 9;
        }
        size_t len = rep ? strlen(rep) : 1;
        if (n + len + 1 > sizeof line) {
            snprintf(err, errlen, "spawn %s: launch command too long", label);
            return -1;
        }
        memcpy(line + n, rep ? rep : p, len);
        n += len;
        p += skip;
    }
    line[n] = 0;
    char *argv[] = {"/bin/sh", "-c", line, NULL};
    return start(s, label, "/bin/sh", argv, NULL, log_path, err, errlen);
}

int spawn_reap(spawn_set *s)
{
    int running = 0;
    for (int i = 0; i < s->count; i++) {
        if (s->relay[i] > 0 && waitpid(s->relay[i], NULL, WNOHANG) == s->relay[i])
            s->relay[i] = 0;
        if (s->exited[i])
            continue;
        int status;
        pid_t r = waitpid(s->pid[i], &status, WNOHANG);
        if (r == s->pid[i]) {
            s->exited[i] = 1;
            s->status[i] = status;
        } else {
            running++;
        }
    }
    return running;
}

void spawn_stop_all(spawn_set *s, int timeout_ms)
{
    for (int i = 0; i < s->count; i++)
        if (!s->exited[i])
            kill(-s->pid[i], SIGTERM);
    struct timespec step = {0, 10 * 1000 * 1000};
    for (int waited = 0; spawn_reap(s) > 0 && waited < timeout_ms; waited += 10)
        nanosleep(&step, NULL);
    for (int i = 0; i < s->count; i++)
        if (!s->exited[i]) {
            fprintf(stderr, "cavelight-master: %s did not stop within %d ms: killed\n", s->label[i], timeout_ms);
            kill(-s->pid[i], SIGKILL);
            waitpid(s->pid[i], &s->status[i], 0);
            s->exited[i] = 1;
        }
    for (int i = 0; i < s->count; i++)
        end_relay(s, i, 1000);
}
