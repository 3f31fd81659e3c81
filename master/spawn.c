#include "spawn.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static int start(spawn_set *s, const char *label, const char *path, char *const argv[], char *err, size_t errlen)
{
    if (s->count >= SPAWN_MAX) {
        snprintf(err, errlen, "spawn %s: more than %d children", label, SPAWN_MAX);
        return -1;
    }
    pid_t parent = getpid();
    pid_t pid = fork();
    if (pid < 0) {
        snprintf(err, errlen, "spawn %s: fork failed: %s", label, strerror(errno));
        return -1;
    }
    if (pid == 0) {
        /* Die with the master, even if it is killed without a chance to clean up. */
        prctl(PR_SET_PDEATHSIG, SIGTERM);
        if (getppid() != parent)
            _exit(127);
        /* Own process group: stopping the child also stops what a launch shell started. */
        setpgid(0, 0);
        execv(path, argv);
        fprintf(stderr, "cavelight-master: cannot run %s: %s\n", path, strerror(errno));
        _exit(127);
    }
    int i = s->count++;
    s->pid[i] = pid;
    s->exited[i] = 0;
    s->status[i] = 0;
    snprintf(s->label[i], sizeof s->label[i], "%s", label);
    return 0;
}

int spawn_local(spawn_set *s, const char *label, char *const argv[], char *err, size_t errlen)
{
    if (access(argv[0], X_OK) != 0) {
        snprintf(err, errlen, "spawn %s: %s is not an executable: build it or pass --node-exe", label, argv[0]);
        return -1;
    }
    return start(s, label, argv[0], argv, err, errlen);
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
                 char *err, size_t errlen)
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
    return start(s, label, "/bin/sh", argv, err, errlen);
}

int spawn_reap(spawn_set *s)
{
    int running = 0;
    for (int i = 0; i < s->count; i++) {
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
}
