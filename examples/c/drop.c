/* A ball dropped on a rigid floor, its contact a bwc law held by a contact element.
 *
 * The host integrates the ball (height y of its lowest point, velocity v, gravity) with a
 * predictor-corrector of step DT: the element gives the impulse of the contact force over
 * each step, from the penetration -y and its rate -v at the step's ends; a scratch copy of
 * the element tries the predicted step, the element itself takes the corrected one. The element finds
 * each contact's onset and separation inside the steps. Prints one line per contact:
 *
 *   bounce N V_IN V_OUT DISSIPATED
 *
 * (impact and rebound speeds in m/s, energy dissipated in the contact so far in J), then
 * the library's one-shot impact of the first contact for comparison:
 *
 *   impact E T_S
 *
 * Build (from the repository's root, after `cargo build --release -p bwc-capi`):
 *   cc -std=c99 -O2 examples/c/drop.c -I crates/capi/include target/release/libbwc.a \
 *      -lm -lpthread -ldl -o drop && ./drop
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bwc.h"

/* Every call's status is checked: on failure, the library says what and why. */
#define CHECK(call)                                                              \
    do {                                                                         \
        if ((call) != BWC_STATUS_OK) {                                           \
            fprintf(stderr, "drop: %s\n", bwc_last_error());                     \
            exit(1);                                                             \
        }                                                                        \
    } while (0)

static const double M = 0.145; /* kg, a baseball */
static const double G = 9.81;  /* m/s^2 */
static const double H0 = 0.1;  /* m, released from rest */
static const double DT = 1e-6; /* s, the host's step */
static const int BOUNCES = 3;

int main(void) {
    /* The BWSHCCM law of the paper's Table 4 (Cross's baseball). */
    BwcLawParams params = {BWC_MODEL_SHCCM, 117080063.0, 5854003.0, 1.1, 1.7,
                           0.1, 981.05, -961.4, 0.925};
    BwcLaw law = 0;
    BwcContact contact = 0;
    CHECK(bwc_law_new(&params, &law));
    BwcElementSettings settings = bwc_element_settings_default();
    settings.policy = BWC_POLICY_CARRY;
    CHECK(bwc_contact_new(law, &settings, &contact));
    BwcContact trial = 0; /* a scratch element for the predictor */
    CHECK(bwc_contact_clone(contact, &trial));

    printf("# contacts of a baseball dropped from %g m (BWSHCCM, Table 4; carry policy):\n", H0);
    printf("# bounce N, impact speed (m/s), rebound speed (m/s), energy dissipated so far (J)\n");
    double y = H0, v = 0.0, force = 0.0, v_in = NAN, first_v_in = NAN;
    int bounces = 0;
    while (bounces < BOUNCES) {
        /* Predict the step's end from the last force, then correct it with the impulse the
         * element gives for the predicted motion; only the corrected step is kept. */
        double v1 = v + (force / M - G) * DT;
        double y1 = y + 0.5 * DT * (v + v1);
        BwcStep step;
        CHECK(bwc_contact_copy(contact, trial));
        CHECK(bwc_contact_advance_penetration(trial, DT, -y, -v, -y1, -v1, &step));
        v1 = v + step.impulse / M - G * DT;
        y1 = y + 0.5 * DT * (v + v1);
        CHECK(bwc_contact_advance_penetration(contact, DT, -y, -v, -y1, -v1, &step));
        if (!isnan(step.began_at)) {
            v_in = G * step.began_at - v;
            if (isnan(first_v_in)) {
                first_v_in = v_in;
            }
        }
        if (!isnan(step.separated_at)) {
            double dissipated;
            CHECK(bwc_contact_dissipated(contact, &dissipated));
            bounces++;
            printf("bounce %d %.17g %.17g %.17g\n", bounces, v_in,
                   v1 + G * (DT - step.separated_at), dissipated);
        }
        y = y1;
        v = v1;
        force = step.force;
    }

    BwcImpact impact;
    CHECK(bwc_impact(law, M, first_v_in, -M * G, &impact));
    printf("# the library's one impact at the first impact speed: impact e, t_s (s)\n");
    printf("impact %.17g %.17g\n", impact.e, impact.t_s);

    CHECK(bwc_contact_free(trial));
    CHECK(bwc_contact_free(contact));
    CHECK(bwc_law_free(law));
    return 0;
}
