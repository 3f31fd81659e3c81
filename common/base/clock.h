/* clock: one monotonic time source for timeouts, deadlines and measured durations.
 *
 * clock_now_ms() reads CLOCK_MONOTONIC in milliseconds as a double: only differences
 * between two readings mean anything (the origin is unspecified, e.g. boot time). It
 * never jumps with wall-clock changes, so deadlines and frame timings stay valid. */
#ifndef CAVELIGHT_CLOCK_H
#define CAVELIGHT_CLOCK_H

double clock_now_ms(void);

#endif
