/* -contact_formulation auto's fitted constants (MMCostModel, src/contact/contactimpl.h; docs/scaling.md,
 * "Refitted with the ranks and the law"), written by scripts/cost_model_fit.py --write from
 * scripts/cost_model_runs.csv, measured by scripts/cost_model_collect.py: refit them, do not edit. */
#define MM_COST_ACTIVE_SET_2D {{-16.02, 1.071, 1.187, 0.1169, -0.00619, 0, 0, 0}, {-10.03, 0.8425, 0}}
#define MM_COST_CONDENSED_2D {{-15.94, 1.155, 0.1492, 0.06502, 0.06159, 0, 0, 0}, {-11.81, 1.109, 0}}
#define MM_COST_ACTIVE_SET_3D {{-13.45, 0.9784, 0.8623, 0.2161, 0.02843, 0, 0, 0}, {-10.02, 0.9205, 0}}
#define MM_COST_CONDENSED_3D {{-15.54, 1.249, 0.2461, -0.03408, 0.2, 0, 0, 0}, {-12.32, 1.252, 0}}
