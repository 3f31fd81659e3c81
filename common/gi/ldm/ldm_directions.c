/* ldm_directions: see ldm_directions.h. */
#include "gi/ldm/ldm_directions.h"

#include <math.h>

static const double PI = 3.14159265358979323846;

/* The partition of the hemisphere into n regions: collars[0] is the cap (1 region);
 * collar c holds count[c] regions between the colatitudes top[c] and top[c + 1]. */
typedef struct zones {
    int collars;
    int count[LDM_DIRECTIONS_MAX];
    double top[LDM_DIRECTIONS_MAX + 1];   /* colatitude of each collar's upper boundary */
    double offset[LDM_DIRECTIONS_MAX];    /* longitude where its first sector starts */
} zones;

/* cos(colatitude) below the first k regions: their area over the hemisphere's, 2 pi. */
static double boundary(int k, int n) { return acos(1.0 - (double)k / n); }

static void partition(int n, zones *z)
{
    z->collars = 1;
    z->count[0] = 1;
    z->top[0] = 0.0;
    z->offset[0] = 0.0;
    if (n == 1) {
        z->top[1] = PI / 2;
        return;
    }
    double cap = boundary(1, n), side = sqrt(2.0 * PI / n); /* an ideal region's side */
    int rings = (int)lround((PI / 2 - cap) / side);
    if (rings < 1)
        rings = 1;
    double width = (PI / 2 - cap) / rings, carry = 0.0;
    int placed = 1;
    for (int r = 0; r < rings; r++) {
        double a = cap + r * width, b = cap + (r + 1) * width;
        /* Regions this ring would hold, with the rounding left over from the rings above
         * (Leopardi's rule), so the counts add up to n. */
        double ideal = (cos(a) - cos(b)) * n + carry;
        int left = rings - r - 1; /* rings still to come, one region each at least */
        int m = left == 0 ? n - placed : (int)lround(ideal);
        if (m > n - placed - left)
            m = n - placed - left;
        if (m < 1)
            m = 1;
        carry = ideal - m;
        z->top[z->collars] = boundary(placed, n);
        z->count[z->collars] = m;
        /* Neighbouring collars' sectors staggered by half a sector. */
        z->offset[z->collars] = (r % 2) * PI / m;
        z->collars++;
        placed += m;
    }
    z->top[z->collars] = PI / 2;
}

int ldm_directions(int n, float (*out)[3])
{
    if (n < 1 || n > LDM_DIRECTIONS_MAX)
        return 0;
    zones z;
    partition(n, &z);
    int k = 0;
    for (int c = 0; c < z.collars; c++) {
        double theta = c == 0 ? 0.0 : 0.5 * (z.top[c] + z.top[c + 1]);
        for (int s = 0; s < z.count[c]; s++, k++) {
            double phi = z.offset[c] + (s + 0.5) * 2.0 * PI / z.count[c];
            out[k][0] = (float)(sin(theta) * cos(phi));
            out[k][1] = (float)cos(theta);
            out[k][2] = (float)(sin(theta) * sin(phi));
        }
    }
    return n;
}

int ldm_direction_region(int n, const float w[3])
{
    if (n < 1 || n > LDM_DIRECTIONS_MAX)
        return -1;
    double x = w[0], y = w[1], zc = w[2];
    if (y < 0) {
        x = -x;
        y = -y;
        zc = -zc;
    }
    zones z;
    partition(n, &z);
    double theta = acos(fmin(y / sqrt(x * x + y * y + zc * zc), 1.0));
    int first = 0;
    for (int c = 0; c < z.collars; c++) {
        if (theta <= z.top[c + 1] || c + 1 == z.collars) {
            double phi = atan2(zc, x) - z.offset[c];
            phi -= 2.0 * PI * floor(phi / (2.0 * PI));
            int s = (int)(phi / (2.0 * PI) * z.count[c]);
            return first + (s < z.count[c] ? s : z.count[c] - 1);
        }
        first += z.count[c];
    }
    return n - 1;
}
