//! Tabulated complex refractive indices `η + ik` of the named metals
//! ([`Metal`](super::Metal)), copied row for row from the published
//! measurements (via the refractiveindex.info database, public domain /
//! CC0, `database/data/<path>.yml`): wavelengths converted from µm to nm,
//! `η` and `k` as printed. Each table keeps the rows from the last one at or
//! below 300 nm to the first at or above 900 nm (the visible range and a
//! margin for renderers that sample 360–830 nm).
// The digits are the publication's (3.14 is a measured η, not π); the rounding
// to f32 is the compiler's.
#![allow(clippy::excessive_precision, clippy::approx_constant)]

use super::MetalTable;

/// Gold: P. B. Johnson and R. W. Christy, "Optical constants of the noble metals", Phys. Rev. B 6, 4370–4379 (1972), doi/ref 10.1103/PhysRevB.6.4370; refractiveindex.info `main/Au/nk/Johnson`.
/// 25 rows, 292.4–984.0 nm.
pub(super) static AU: MetalTable = MetalTable {
    source: "P. B. Johnson and R. W. Christy, \"Optical constants of the noble metals\", Phys. Rev. B 6, 4370–4379 (1972)",
    doi: "10.1103/PhysRevB.6.4370",
    lambda_nm: &[
        292.4, 300.9, 310.7, 320.4, 331.5, 342.5, 354.2, 367.9, 381.5, 397.4, 413.3, 430.5, 450.9, 471.4,
        495.9, 520.9, 548.6, 582.1, 616.8, 659.5, 704.5, 756.0, 821.1, 892.0, 984.0,
    ],
    eta: &[
        1.49, 1.53, 1.53, 1.54, 1.48, 1.48, 1.50, 1.48, 1.46, 1.47, 1.46, 1.45, 1.38, 1.31, 1.04, 0.62, 0.43,
        0.29, 0.21, 0.14, 0.13, 0.14, 0.16, 0.17, 0.22,
    ],
    k: &[
        1.878, 1.889, 1.893, 1.898, 1.883, 1.871, 1.866, 1.895, 1.933, 1.952, 1.958, 1.948, 1.914, 1.849,
        1.833, 2.081, 2.455, 2.863, 3.272, 3.697, 4.103, 4.542, 5.083, 5.663, 6.350,
    ],
};

/// Silver: P. B. Johnson and R. W. Christy, "Optical constants of the noble metals", Phys. Rev. B 6, 4370–4379 (1972), doi/ref 10.1103/PhysRevB.6.4370; refractiveindex.info `main/Ag/nk/Johnson`.
/// 25 rows, 292.4–984.0 nm.
pub(super) static AG: MetalTable = MetalTable {
    source: "P. B. Johnson and R. W. Christy, \"Optical constants of the noble metals\", Phys. Rev. B 6, 4370–4379 (1972)",
    doi: "10.1103/PhysRevB.6.4370",
    lambda_nm: &[
        292.4, 300.9, 310.7, 320.4, 331.5, 342.5, 354.2, 367.9, 381.5, 397.4, 413.3, 430.5, 450.9, 471.4,
        495.9, 520.9, 548.6, 582.1, 616.8, 659.5, 704.5, 756.0, 821.1, 892.0, 984.0,
    ],
    eta: &[
        1.39, 1.34, 1.13, 0.81, 0.17, 0.14, 0.10, 0.07, 0.05, 0.05, 0.05, 0.04, 0.04, 0.05, 0.05, 0.05, 0.06,
        0.05, 0.06, 0.05, 0.04, 0.03, 0.04, 0.04, 0.04,
    ],
    k: &[
        1.161, 0.964, 0.616, 0.392, 0.829, 1.142, 1.419, 1.657, 1.864, 2.070, 2.275, 2.462, 2.657, 2.869,
        3.093, 3.324, 3.586, 3.858, 4.152, 4.483, 4.838, 5.242, 5.727, 6.312, 6.992,
    ],
};

/// Copper: P. B. Johnson and R. W. Christy, "Optical constants of the noble metals", Phys. Rev. B 6, 4370–4379 (1972), doi/ref 10.1103/PhysRevB.6.4370; refractiveindex.info `main/Cu/nk/Johnson`.
/// 25 rows, 292.4–984.0 nm.
pub(super) static CU: MetalTable = MetalTable {
    source: "P. B. Johnson and R. W. Christy, \"Optical constants of the noble metals\", Phys. Rev. B 6, 4370–4379 (1972)",
    doi: "10.1103/PhysRevB.6.4370",
    lambda_nm: &[
        292.4, 300.9, 310.7, 320.4, 331.5, 342.5, 354.2, 367.9, 381.5, 397.4, 413.3, 430.5, 450.9, 471.4,
        495.9, 520.9, 548.6, 582.1, 616.8, 659.5, 704.5, 756.0, 821.1, 892.0, 984.0,
    ],
    eta: &[
        1.42, 1.40, 1.38, 1.38, 1.34, 1.36, 1.37, 1.36, 1.33, 1.32, 1.28, 1.25, 1.24, 1.25, 1.22, 1.18, 1.02,
        0.70, 0.30, 0.22, 0.21, 0.24, 0.26, 0.30, 0.32,
    ],
    k: &[
        1.633, 1.679, 1.729, 1.783, 1.821, 1.864, 1.916, 1.975, 2.045, 2.116, 2.207, 2.305, 2.397, 2.483,
        2.564, 2.608, 2.577, 2.704, 3.205, 3.747, 4.205, 4.665, 5.180, 5.768, 6.421,
    ],
};

/// Aluminium: A. D. Rakić, "Algorithm for the determination of intrinsic optical constants of metal films: application to aluminum", Appl. Opt. 34, 4755–4767 (1995), doi/ref 10.1364/AO.34.004755; refractiveindex.info `main/Al/nk/Rakic`.
/// 19 rows, 247.97–911.66 nm.
pub(super) static AL: MetalTable = MetalTable {
    source: "A. D. Rakić, \"Algorithm for the determination of intrinsic optical constants of metal films: application to aluminum\", Appl. Opt. 34, 4755–4767 (1995)",
    doi: "10.1364/AO.34.004755",
    lambda_nm: &[
        247.97, 309.96, 326.28, 364.66, 413.28, 442.8, 476.87, 516.6, 563.57, 619.93, 652.25, 688.81, 729.32,
        774.91, 794.78, 815.69, 837.74, 885.61, 911.66,
    ],
    eta: &[
        0.18137, 0.28003, 0.31474, 0.39877, 0.52135, 0.6079, 0.7278, 0.8734, 1.0728, 1.366, 1.5724, 1.8301,
        2.1606, 2.6154, 2.7675, 2.7668, 2.6945, 2.2802, 1.9739,
    ],
    k: &[
        2.9029, 3.7081, 3.9165, 4.3957, 5.0008, 5.3676, 5.7781, 6.2418, 6.7839, 7.4052, 7.7354, 8.0601,
        8.3565, 8.4914, 8.3866, 8.2573, 8.1878, 8.1134, 8.3058,
    ],
};

/// Chromium: P. B. Johnson and R. W. Christy, "Optical constants of transition metals: Ti, V, Cr, Mn, Fe, Co, Ni, and Pd", Phys. Rev. B 9, 5056–5070 (1974), doi/ref 10.1103/PhysRevB.9.5056; refractiveindex.info `main/Cr/nk/Johnson`.
/// 25 rows, 292.0–984.0 nm.
pub(super) static CR: MetalTable = MetalTable {
    source: "P. B. Johnson and R. W. Christy, \"Optical constants of transition metals: Ti, V, Cr, Mn, Fe, Co, Ni, and Pd\", Phys. Rev. B 9, 5056–5070 (1974)",
    doi: "10.1103/PhysRevB.9.5056",
    lambda_nm: &[
        292.0, 301.0, 311.0, 320.0, 332.0, 342.0, 354.0, 368.0, 381.0, 397.0, 413.0, 431.0, 451.0, 471.0,
        496.0, 521.0, 549.0, 582.0, 617.0, 659.0, 704.0, 756.0, 821.0, 892.0, 984.0,
    ],
    eta: &[
        1.48, 1.53, 1.58, 1.65, 1.69, 1.76, 1.84, 1.87, 1.92, 2.00, 2.08, 2.19, 2.33, 2.51, 2.75, 2.94, 3.18,
        3.22, 3.17, 3.09, 3.05, 3.08, 3.20, 3.30, 3.41,
    ],
    k: &[
        2.28, 2.34, 2.40, 2.47, 2.53, 2.58, 2.64, 2.69, 2.74, 2.83, 2.93, 3.04, 3.14, 3.24, 3.30, 3.33, 3.33,
        3.30, 3.30, 3.34, 3.39, 3.42, 3.48, 3.52, 3.57,
    ],
};

/// Iron: P. B. Johnson and R. W. Christy, "Optical constants of transition metals: Ti, V, Cr, Mn, Fe, Co, Ni, and Pd", Phys. Rev. B 9, 5056–5070 (1974), doi/ref 10.1103/PhysRevB.9.5056; refractiveindex.info `main/Fe/nk/Johnson`.
/// 25 rows, 292.0–984.0 nm.
pub(super) static FE: MetalTable = MetalTable {
    source: "P. B. Johnson and R. W. Christy, \"Optical constants of transition metals: Ti, V, Cr, Mn, Fe, Co, Ni, and Pd\", Phys. Rev. B 9, 5056–5070 (1974)",
    doi: "10.1103/PhysRevB.9.5056",
    lambda_nm: &[
        292.0, 301.0, 311.0, 320.0, 332.0, 342.0, 354.0, 368.0, 381.0, 397.0, 413.0, 431.0, 451.0, 471.0,
        496.0, 521.0, 549.0, 582.0, 617.0, 659.0, 704.0, 756.0, 821.0, 892.0, 984.0,
    ],
    eta: &[
        1.65, 1.67, 1.69, 1.74, 1.78, 1.85, 1.93, 2.02, 2.12, 2.24, 2.35, 2.48, 2.59, 2.67, 2.74, 2.86, 2.95,
        2.94, 2.88, 2.92, 2.86, 2.87, 2.94, 2.96, 2.92,
    ],
    k: &[
        1.94, 2.00, 2.06, 2.12, 2.19, 2.27, 2.35, 2.43, 2.50, 2.58, 2.65, 2.71, 2.77, 2.82, 2.88, 2.91, 2.93,
        2.99, 3.05, 3.10, 3.19, 3.28, 3.39, 3.56, 3.79,
    ],
};

/// Nickel: P. B. Johnson and R. W. Christy, "Optical constants of transition metals: Ti, V, Cr, Mn, Fe, Co, Ni, and Pd", Phys. Rev. B 9, 5056–5070 (1974), doi/ref 10.1103/PhysRevB.9.5056; refractiveindex.info `main/Ni/nk/Johnson`.
/// 25 rows, 292.0–984.0 nm.
pub(super) static NI: MetalTable = MetalTable {
    source: "P. B. Johnson and R. W. Christy, \"Optical constants of transition metals: Ti, V, Cr, Mn, Fe, Co, Ni, and Pd\", Phys. Rev. B 9, 5056–5070 (1974)",
    doi: "10.1103/PhysRevB.9.5056",
    lambda_nm: &[
        292.0, 301.0, 311.0, 320.0, 332.0, 342.0, 354.0, 368.0, 381.0, 397.0, 413.0, 431.0, 451.0, 471.0,
        496.0, 521.0, 549.0, 582.0, 617.0, 659.0, 704.0, 756.0, 821.0, 892.0, 984.0,
    ],
    eta: &[
        2.03, 2.02, 2.01, 1.93, 1.84, 1.78, 1.74, 1.70, 1.72, 1.72, 1.70, 1.71, 1.73, 1.78, 1.82, 1.85, 1.92,
        1.96, 1.99, 1.99, 2.06, 2.13, 2.26, 2.40, 2.48,
    ],
    k: &[
        2.20, 2.18, 2.18, 2.19, 2.22, 2.26, 2.32, 2.40, 2.48, 2.57, 2.69, 2.82, 2.95, 3.09, 3.25, 3.42, 3.61,
        3.80, 4.02, 4.26, 4.50, 4.73, 4.97, 5.23, 5.55,
    ],
};

/// Titanium: P. B. Johnson and R. W. Christy, "Optical constants of transition metals: Ti, V, Cr, Mn, Fe, Co, Ni, and Pd", Phys. Rev. B 9, 5056–5070 (1974), doi/ref 10.1103/PhysRevB.9.5056; refractiveindex.info `main/Ti/nk/Johnson`.
/// 25 rows, 292.0–984.0 nm.
pub(super) static TI: MetalTable = MetalTable {
    source: "P. B. Johnson and R. W. Christy, \"Optical constants of transition metals: Ti, V, Cr, Mn, Fe, Co, Ni, and Pd\", Phys. Rev. B 9, 5056–5070 (1974)",
    doi: "10.1103/PhysRevB.9.5056",
    lambda_nm: &[
        292.0, 301.0, 311.0, 320.0, 332.0, 342.0, 354.0, 368.0, 381.0, 397.0, 413.0, 431.0, 451.0, 471.0,
        496.0, 521.0, 549.0, 582.0, 617.0, 659.0, 704.0, 756.0, 821.0, 892.0, 984.0,
    ],
    eta: &[
        1.40, 1.45, 1.50, 1.55, 1.61, 1.72, 1.82, 1.90, 1.99, 2.08, 2.14, 2.21, 2.27, 2.32, 2.36, 2.44, 2.54,
        2.60, 2.67, 2.76, 2.86, 3.00, 3.21, 3.29, 3.35,
    ],
    k: &[
        2.36, 2.46, 2.57, 2.66, 2.74, 2.82, 2.87, 2.90, 2.93, 2.95, 2.98, 3.01, 3.04, 3.10, 3.19, 3.30, 3.43,
        3.58, 3.72, 3.84, 3.96, 4.01, 4.01, 3.96, 3.97,
    ],
};

/// Platinum: A. D. Rakić, A. B. Djurišić, J. M. Elazar and M. L. Majewski, "Optical properties of metallic films for vertical-cavity optoelectronic devices", Appl. Opt. 37, 5271–5283 (1998) (Lorentz–Drude fit to measured data; every 4th row of the database's tabulation of the model), doi/ref 10.1364/AO.37.005271; refractiveindex.info `main/Pt/nk/Rakic-LD`.
/// 72 rows, 299.25–902.85 nm.
pub(super) static PT: MetalTable = MetalTable {
    source: "A. D. Rakić, A. B. Djurišić, J. M. Elazar and M. L. Majewski, \"Optical properties of metallic films for vertical-cavity optoelectronic devices\", Appl. Opt. 37, 5271–5283 (1998) (Lorentz–Drude fit to measured data; every 4th row of the database's tabulation of the model)",
    doi: "10.1364/AO.37.005271",
    lambda_nm: &[
        299.25, 303.97, 308.77, 313.64, 318.6, 323.62, 328.73, 333.92, 339.2, 344.55, 349.99, 355.52, 361.13,
        366.83, 372.62, 378.5, 384.48, 390.55, 396.71, 402.98, 409.34, 415.8, 422.36, 429.03, 435.81, 442.69,
        449.67, 456.77, 463.98, 471.31, 478.75, 486.31, 493.99, 501.78, 509.71, 517.75, 525.93, 534.23,
        542.66, 551.23, 559.93, 568.77, 577.75, 586.87, 596.14, 605.55, 615.11, 624.82, 634.68, 644.7,
        654.88, 665.22, 675.72, 686.39, 697.23, 708.23, 719.41, 730.77, 742.31, 754.03, 765.93, 778.02,
        790.31, 802.78, 815.46, 828.33, 841.41, 854.69, 868.18, 881.89, 895.81, 902.85,
    ],
    eta: &[
        1.477, 1.4842, 1.4924, 1.5016, 1.5117, 1.5226, 1.5343, 1.5468, 1.56, 1.5737, 1.588, 1.6028, 1.6181,
        1.6337, 1.6496, 1.6658, 1.6821, 1.6987, 1.7153, 1.7321, 1.7489, 1.7657, 1.7826, 1.7995, 1.8164,
        1.8333, 1.8503, 1.8674, 1.8846, 1.9019, 1.9194, 1.9372, 1.9552, 1.9736, 1.9923, 2.0115, 2.0312,
        2.0515, 2.0724, 2.0939, 2.1161, 2.1391, 2.1629, 2.1875, 2.213, 2.2393, 2.2666, 2.2948, 2.3239,
        2.3539, 2.3848, 2.4167, 2.4494, 2.4831, 2.5175, 2.5528, 2.5889, 2.6257, 2.6632, 2.7014, 2.7401,
        2.7794, 2.8192, 2.8595, 2.9001, 2.9411, 2.9823, 3.0238, 3.0656, 3.1075, 3.1495, 3.1706,
    ],
    k: &[
        2.1586, 2.196, 2.2336, 2.2713, 2.3091, 2.347, 2.3848, 2.4226, 2.4603, 2.498, 2.5355, 2.5729, 2.6102,
        2.6474, 2.6846, 2.7216, 2.7587, 2.7958, 2.8329, 2.8701, 2.9075, 2.945, 2.9829, 3.021, 3.0595, 3.0985,
        3.1379, 3.1779, 3.2184, 3.2596, 3.3014, 3.3439, 3.3872, 3.4311, 3.4759, 3.5213, 3.5676, 3.6145,
        3.6622, 3.7106, 3.7597, 3.8094, 3.8598, 3.9107, 3.9622, 4.0141, 4.0665, 4.1192, 4.1723, 4.2256,
        4.2792, 4.333, 4.3869, 4.4408, 4.4948, 4.5488, 4.6028, 4.6567, 4.7105, 4.7641, 4.8177, 4.8711,
        4.9244, 4.9775, 5.0305, 5.0834, 5.1363, 5.1892, 5.2421, 5.295, 5.3482, 5.3748,
    ],
};

/// Brass (Cu 70 %, Zn 30 %): M. R. Querry, "Optical constants", Contractor Report CRDC-CR-85034 (1985), 70 % Cu, 30 % Zn, doi/ref DTIC ADA158623; refractiveindex.info `other/alloys/Cu-Zn/nk/Querry-Cu70Zn30`.
/// 61 rows, 300.0–900.0 nm.
pub(super) static BRASS: MetalTable = MetalTable {
    source: "M. R. Querry, \"Optical constants\", Contractor Report CRDC-CR-85034 (1985), 70 % Cu, 30 % Zn",
    doi: "DTIC ADA158623",
    lambda_nm: &[
        300.0, 310.0, 320.0, 330.0, 340.0, 350.0, 360.0, 370.0, 380.0, 390.0, 400.0, 410.0, 420.0, 430.0,
        440.0, 450.0, 460.0, 470.0, 480.0, 490.0, 500.0, 510.0, 520.0, 530.0, 540.0, 550.0, 560.0, 570.0,
        580.0, 590.0, 600.0, 610.0, 620.0, 630.0, 640.0, 650.0, 660.0, 670.0, 680.0, 690.0, 700.0, 710.0,
        720.0, 730.0, 740.0, 750.0, 760.0, 770.0, 780.0, 790.0, 800.0, 810.0, 820.0, 830.0, 840.0, 850.0,
        860.0, 870.0, 880.0, 890.0, 900.0,
    ],
    eta: &[
        1.388, 1.419, 1.446, 1.473, 1.494, 1.504, 1.503, 1.497, 1.487, 1.471, 1.445, 1.405, 1.350, 1.278,
        1.191, 1.094, 0.994, 0.900, 0.816, 0.745, 0.686, 0.639, 0.602, 0.573, 0.549, 0.527, 0.505, 0.484,
        0.468, 0.460, 0.450, 0.452, 0.449, 0.445, 0.444, 0.444, 0.445, 0.444, 0.444, 0.445, 0.446, 0.448,
        0.450, 0.452, 0.455, 0.457, 0.458, 0.460, 0.464, 0.469, 0.473, 0.478, 0.481, 0.483, 0.486, 0.490,
        0.494, 0.500, 0.507, 0.515, 0.523,
    ],
    k: &[
        1.731, 1.764, 1.789, 1.807, 1.815, 1.815, 1.815, 1.818, 1.818, 1.813, 1.805, 1.794, 1.786, 1.784,
        1.797, 1.829, 1.883, 1.957, 2.046, 2.145, 2.250, 2.358, 2.464, 2.568, 2.668, 2.765, 2.860, 2.958,
        3.059, 3.159, 3.253, 3.345, 3.434, 3.522, 3.609, 3.695, 3.778, 3.860, 3.943, 4.025, 4.106, 4.186,
        4.266, 4.346, 4.424, 4.501, 4.579, 4.657, 4.737, 4.814, 4.890, 4.965, 5.039, 5.115, 5.192, 5.269,
        5.346, 5.423, 5.500, 5.575, 5.650,
    ],
};
