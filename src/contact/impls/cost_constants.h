/* -contact_formulation auto's fitted constants (MMCostModel, src/contact/contactimpl.h; docs/scaling.md,
 * "Refitted with the ranks and the law"), written by scripts/cost_model_fit.py --write from
 * scripts/cost_model_runs.csv, measured by scripts/cost_model_collect.py: refit them, do not edit. */
#define MM_COST_ACTIVE_SET_2D {{-15.24, 1.058, 0.8858, -0.6145, 0.4106, 4.821, 4.467, -0.4437, -0.4041}, {-8.367, 0.6998, 2.407, -0.1437}}
#define MM_COST_CONDENSED_2D {{-14.81, 1.048, 0.328, -0.0748, 0.05843, 2.095, 3.378, -0.3104, -0.1171}, {-10.48, 0.9994, 2.96, -0.2398}}
#define MM_COST_ACTIVE_SET_3D {{-13.69, 0.9812, 1.107, 0.2067, 0.04862, 1.075, -0.006254, 0.1246, -0.1178}, {-9.726, 0.892, 0.8582, -0.0797}}
#define MM_COST_CONDENSED_3D {{-15.61, 1.243, 0.4308, -0.1183, 0.2174, 1.292, 1.772, -0.0834, -0.1258}, {-12, 1.221, 0.1524, 0.003981}}
