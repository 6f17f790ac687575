"""Numbers transcribed from the seed paper (Qian et al., Sci. Rep.), simulation sections."""

#: Table 3 (geometric errors, n = 20,000): quantity -> (mean, std, max, min) [mm]; "Δp" is |p'| - |p| (NOTES_SEED.md).
TABLE3 = {
    "dp_reach_mm": (0.0112, 0.1105, 0.4754, -0.3804),
    "dx_mm": (-4.71e-5, 0.1389, 0.5672, -0.6406),
    "dy_mm": (1.59e-4, 0.0822, 0.2991, -0.3574),
    "dz_mm": (2.54e-4, 0.1414, 0.5389, -0.6547),
}
#: Eq. 26: P(|ΔP| < T) at T = 0.15 and 0.25 mm; P(|Δangle| < 0.002 rad) per Euler angle (as printed).
RELIABILITY = {0.15: 0.7639, 0.25: 0.9503}
ANGLE_RELIABILITY_0002 = (0.7639, 0.8458, 0.9855)
#: Table 5 (joint clearance): quantity -> (mean, std, max, min) [mm / rad].
TABLE5 = {
    "dp_reach_mm": (-0.2669, 0.4281, 1.557, -1.3677),
    "dx_mm": (1.0033, 0.4835, 2.9457, -0.8082),
    "dy_mm": (5.1599e-4, 0.2985, 1.0452, -1.0669),
    "dz_mm": (-9.0025e-4, 0.3853, 1.3884, -1.3202),
    "dalpha_rad": (-9.9408e-7, 2.1801e-4, 9.5873e-4, -9.3875e-4),  # paper: Δφ
    "dbeta_rad": (6.8450e-7, 1.5260e-4, 6.5689e-4, -6.7131e-4),  # paper: Δθ
    "dgamma_rad": (2.9981e-7, 6.9772e-5, 3.0010e-4, -3.0719e-4),  # paper: Δψ
}
#: The paper's stated ideal end-effector position (no unit given).
IDEAL_POSITION = (-0.0924, 0.1609, -1.5119)
#: Sensitivity claims (text around Figs. 7-9 and 13).
CLAIMS = {
    "fig7": "position error most sensitive to the lengths of links 3 and 4",
    "fig8": "position error most sensitive to the angle errors of joints 2 and 3",
    "fig9": "theta1 and theta2 have no effect on beta; theta6 has the greatest effect on alpha",
    "fig13": "clearance offsets of joints 2, 3, 5 dominate x (max 0.394 mm); joints 1, 6 dominate y (-0.263 mm) and z (0.188 mm)",
}
