//! The Dormand-Prince 5(4) pair (DOPRI5) with Hairer's 4th-order dense output.
//!
//! J. R. Dormand, P. J. Prince, *A family of embedded Runge-Kutta formulae*, J. Comput. Appl.
//! Math. 6 (1980) 19-26; dense output as in Hairer's `dopri5.f` (Hairer, Nørsett & Wanner,
//! *Solving ODEs I*, Sec. II.6).

use crate::tableau::{ErrorEstimate, Interpolant, StiffnessTest, Tableau};

const B: [f64; 7] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
    0.0,
];

/// DOPRI5: 7 stages, the last one is `f(t + h, y_1)` (first same as last).
pub static DOPRI5: Tableau = Tableau {
    name: "DOPRI5",
    order: 5,
    error_order: 4,
    stages: 7,
    fsal: 6,
    c: &[0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0],
    a: &[
        &[],
        &[1.0 / 5.0],
        &[3.0 / 40.0, 9.0 / 40.0],
        &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
        &[
            19372.0 / 6561.0,
            -25360.0 / 2187.0,
            64448.0 / 6561.0,
            -212.0 / 729.0,
        ],
        &[
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
        ],
        &[B[0], B[1], B[2], B[3], B[4], B[5]],
    ],
    b: &B,
    // e = b - b̂ (5th minus 4th order).
    error: ErrorEstimate::Embedded(&[
        71.0 / 57600.0,
        0.0,
        -71.0 / 16695.0,
        71.0 / 1920.0,
        -17253.0 / 339200.0,
        22.0 / 525.0,
        -1.0 / 40.0,
    ]),
    interpolant: Interpolant {
        order: 4,
        rows: &[
            // F_0 = y_1 - y
            &[B[0], B[1], B[2], B[3], B[4], B[5], B[6]],
            // F_1 = h k_0 - F_0
            &[1.0 - B[0], -B[1], -B[2], -B[3], -B[4], -B[5], -B[6]],
            // F_2 = F_0 - h k_6 - F_1
            &[
                2.0 * B[0] - 1.0,
                2.0 * B[1],
                2.0 * B[2],
                2.0 * B[3],
                2.0 * B[4],
                2.0 * B[5],
                2.0 * B[6] - 1.0,
            ],
            // F_3: Hairer's d coefficients
            &[
                -12715105075.0 / 11282082432.0,
                0.0,
                87487479700.0 / 32700410799.0,
                -10690763975.0 / 1880347072.0,
                701980252875.0 / 199316789632.0,
                -1453857185.0 / 822651844.0,
                69997945.0 / 29380423.0,
            ],
        ],
    },
    default_beta: 0.04,
    stiffness: StiffnessTest {
        stage: 5,
        bound: 3.306,
    },
};
