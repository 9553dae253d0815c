"""The laws of the paper's Table 4 (tab:RCross): the BWSHCCM and the BWMCM of Cross's baseball
(Cross 2011, Fig. 9.5) of mass CROSS_MASS on a flat surface, SI units; the same as
`bw_models::published` and `fixtures/cross_*.toml`."""

CROSS_MASS = 0.145  # kg

CROSS_BWSHCCM = {"k": 117080063.0, "c": 5854003.0, "n": 1.1, "p": 1.7, "alpha": 0.1,
                 "beta": 981.05, "gamma": -961.4, "A": 0.925}

CROSS_BWMCM = {"k": 253000000.0, "c": 2811.0, "n": 1.2, "p": 1.8, "alpha": 0.15,
               "beta": 1200.0, "gamma": -1200.0, "A": 1.01}
