/* -contact_formulation auto's fitted constants (MMCostModel, src/contact/contactimpl.h; docs/scaling.md,
 * "Refitted with the ranks and the law"), written by scripts/cost_model_fit.py --write from
 * scripts/cost_model_runs.csv, measured by scripts/cost_model_collect.py: refit them, do not edit. */
#define MM_COST_ACTIVE_SET_2D {{-14.34, 0.9523, 0.6025, 0.08719, 0.08633, 1.927, 3.777, -0.3752, -0.2702}, {-8.345, 0.6757, 0.7218, -0.1018}}
#define MM_COST_CONDENSED_2D {{-14.13, 0.9894, 0.06219, 0.03288, 0.03098, 1.197, 3.058, -0.2919, -0.2004}, {-10.26, 0.9514, 1.475, -0.2077}}
#define MM_COST_ACTIVE_SET_3D {{-13.79, 0.9971, 0.6515, 0.192, 0.1422, 1.169, 0.7164, 0.07026, -0.1697}, {-9.708, 0.8851, 0.8882, -0.1287}}
#define MM_COST_CONDENSED_3D {{-15.59, 1.252, 0.1647, -0.03453, 0.1967, 1.291, 1.307, -0.000923, -0.202}, {-11.85, 1.192, 0.7078, -0.1057}}
