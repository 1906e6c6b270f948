/* -contact_formulation auto's fitted constants (MMCostModel, src/contact/contactimpl.h; docs/scaling.md,
 * "Refitted with the ranks and the law"), written by scripts/cost_model_fit.py --write from
 * scripts/cost_model_runs.csv and scripts/cost_model_linear_runs.csv, measured by scripts/cost_model_collect.py: refit them, do not edit. */
#define MM_COST_ACTIVE_SET_2D {{-13.82, 0.9153, 0.5421, 0.0975, 0.07228, 0.6546, 1.634, -0.2189, -0.1549, 0.3921, 0.8379}, {-8.034, 0.6473, 0.6786, -0.08261}}
#define MM_COST_CG_2D {{-14.33, 1.007, 0.4948, 0, 0, -0.006037, 0.5812, 0.03513, -0.03439, 0.02559, 0}, {-8.157, 0.677, 0.7692, -0.09998}}
#define MM_COST_CONDENSED_2D {{-13.66, 0.9569, 0.004745, -0.04066, 0.07317, 0.6333, 1.592, -0.2278, -0.1554, 0.2756, 0.9187}, {-9.809, 0.9096, 1.245, -0.1698}}
#define MM_COST_FACTOR_2D {{-13.45, 0.9274, -0.05109, 0, 0, 0.786, -0.3173, 0.1418, -0.1574, 0.05033, 0}, {-9.85, 0.9312, 1.303, -0.1826}}
#define MM_COST_ACTIVE_SET_3D {{-13.76, 0.9905, 0.7146, 0.2595, 0.05734, 0.7321, 1.236, -0.05091, -0.1458, 0.3249, 0.6388}, {-9.569, 0.8722, 1.112, -0.133}}
#define MM_COST_CG_3D {{-14.29, 1.078, 0.6118, 0, 0, -0.4288, 0.3944, 0.1061, -0.02863, 0.4677, 0}, {-9.531, 0.8841, 1.107, -0.1534}}
#define MM_COST_CONDENSED_3D {{-15.55, 1.24, 0.2454, -0.0109, 0.1754, 1.182, 2.082, -0.1565, -0.206, 0.4125, 0.6493}, {-11.68, 1.177, 0.8446, -0.09955}}
#define MM_COST_FACTOR_3D {{-14.82, 1.189, -0.1608, 0, 0, 0.7979, -0.456, 0.2294, -0.1544, -0.01782, 0}, {-11.84, 1.213, 1.102, -0.1465}}
#define MM_COST_DIRECT_MARGIN 0.1 /* a direct solve within it of the cheapest prediction is taken */
