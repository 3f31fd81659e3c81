/* spawn: the master's child processes (nodes on this machine, or launch commands that
 * start nodes on their hosts).
 *
 * spawn_local() runs a program directly; spawn_remote() runs the config's launch
 * template through /bin/sh with {host} and {command} replaced (ssh by default, like
 * Equalizer's launch command). Each child leads its own process group and gets SIGTERM
 * if the master dies (PR_SET_PDEATHSIG); spawn_stop_all() sends SIGTERM to each group,
 * waits, then SIGKILLs what is left. A child's standard output and error go to the master's
 * standard error and, when a log file is given (created, or emptied), to that file too,
 * through a small relay process per child that ends when the child's output does. */
#ifndef CAVELIGHT_SPAWN_H
#define CAVELIGHT_SPAWN_H

#include <stddef.h>
#include <stdio.h>
#include <sys/types.h>

enum { SPAWN_MAX = 64 };

typedef struct spawn_set {
    int count;
    pid_t pid[SPAWN_MAX];
    char label[SPAWN_MAX][64];
    int exited[SPAWN_MAX];
    int status[SPAWN_MAX];
    char log[SPAWN_MAX][1024]; /* "" = the master's output */
    pid_t relay[SPAWN_MAX];    /* copies the child's output to its log and the master's; 0: none */
} spawn_set;

/* argv is NULL-terminated; argv[0] is the program; it runs in workdir (NULL: the master's).
 * log_path may be NULL. Returns 0 or -1 with err. */
int spawn_local(spawn_set *s, const char *label, char *const argv[], const char *workdir,
                const char *log_path, char *err, size_t errlen);
/* Builds the shell command from template (with {host}, {command}) and runs it. */
int spawn_remote(spawn_set *s, const char *label, const char *launch_template, const char *host,
                 const char *command, const char *log_path, char *err, size_t errlen);
/* The index of the child with this label, or -1. */
int spawn_find(const spawn_set *s, const char *label);
/* Writes the last `lines` lines of child i's log to f, each after prefix. */
void spawn_log_tail(spawn_set *s, int i, int lines, const char *prefix, FILE *f);
/* Reaps exited children without blocking; returns how many are still running. */
int spawn_reap(spawn_set *s);
/* SIGTERM to all, wait up to timeout_ms, then SIGKILL. */
void spawn_stop_all(spawn_set *s, int timeout_ms);
/* Quotes s for /bin/sh into out (single quotes). Returns 0, or -1 if out is too small. */
int spawn_shell_quote(const char *s, char *out, size_t cap);

#endif
