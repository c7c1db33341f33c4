"""The paper's figure and table captions, verbatim from the preprint (doi 10.20944/preprints202501.1517.v1).

Used by :mod:`moving_bogie.paper.registry` to show each rebuilt artifact next to the caption it reproduces.
The text is the print's, including its inline TeX and bold markers; only the leading label
("**Figure 5.**") is split off into :attr:`Caption.label`. Where the print labels an artifact
differently from the text that cites it, :attr:`Caption.printed_label` keeps the print's label.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["CAPTIONS", "Caption"]


@dataclass(frozen=True)
class Caption:
    """One caption of the paper.

    Attributes
    ----------
    id : str
        Stable identifier used for file names: ``"table2"``, ``"figure5"``, ``"figureA3"``.
    label : str
        How the paper's text cites it: ``"Figure 5"``, ``"Figure A3"``.
    text : str
        The caption as printed, after the label.
    printed_label : str
        The label as printed when it differs from `label` (else ``""``).
    """

    id: str
    label: str
    text: str
    printed_label: str = ""


_TIME_SERIES_FULL = (
    "Full lines are for finite beam and dashed ones for infinite one calculated using closed-form formulas."
)

#: Every caption of the paper, in the paper's order.
CAPTIONS: tuple[Caption, ...] = (
    Caption(
        "figure1",
        "Figure 1",
        "One-layer model: (a) traversed by two masses; (b) traversed by a single bogie.",
    ),
    Caption("table1", "Table 1", "Input data of cases analyzed in time series."),
    Caption("table2", "Table 2", "Induced frequencies of analyzed cases."),
    Caption(
        "figure2",
        "Figure 2",
        "The real (blue) and imaginary (orange) parts of the induced frequencies in Case 1. Only one root "
        "of each pair is plotted, the other root has equal imaginary part but opposite real part.",
    ),
    Caption(
        "figure3",
        "Figure 3",
        "Instability lines of two moving proximate masses of the same value. Different colors stand for "
        "different distances  $\\tilde{d} = 1 : 0.25 : 2.25$  as indicated in the legend. Black dotted "
        "line marks the critical velocity. Parts (a) to (f) correspond to  $\\eta_f = 0.05 : 0.05 : 0.3$ .",
    ),
    Caption(
        "figure4",
        "Figure 4",
        "Instability lines. Different colors stand for different distances  $\\tilde{d} = 1:0.25:2.25$  as "
        "indicated in the legend. Full lines are for a moving bogie and dashed lines for two moving masses, "
        "'a' means that these curves were adapted to represent the same total mass. Parts (a) to (f) "
        "correspond to  $\\eta_f = 0.05:0.05:0.3$ .",
    ),
    Caption(
        "figure5",
        "Figure 5",
        f"Time series in Case1. {_TIME_SERIES_FULL} (a) beam deflection at the rear mass, (b) bogie bar "
        "mass center displacement, (c) bogie bar mass center rotation.",
    ),
    Caption(
        "figure6",
        "Figure 6",
        "Time series in Case1. **(a)** beam deflection at the rear mass, **(b)** bogie bar mass center "
        "displacement.",
    ),
    Caption(
        "figure7",
        "Figure 7",
        "Instability lines for a moving bogie. Different colors stand for different distances  "
        "$\\tilde{d} = 1:0.25:2$  as indicated in the legend. Full curves are for no damping in suspension "
        "and dashed curves are for suspension damping of  $\\eta_v = 0.05$ . (a)  $cf_2 = 0.1$ ; (b)  "
        "$cf_2 = 0.01$ .",
    ),
    Caption(
        "figure8",
        "Figure 8",
        "Instability lines for a moving bogie. Different colors stand for different distances  "
        "$\\tilde{d} = 1:0.25:2.25$  as indicated in the legend. Full curves are for the Euler-Bernoulli "
        "theory and dashed curves for the Timoshenko-Rayleigh. (a)  $\\tilde{S} = 100$ ,  "
        "$\\tilde{r} = 0.03$ ; (b)  $\\tilde{S} = 10$ ,  $\\tilde{r} = 0.09$ .",
    ),
    Caption(
        "figure9",
        "Figure 9",
        f"Time series in Case 2. {_TIME_SERIES_FULL} **(a)** beam deflection at the rear mass, **(b)** "
        "bogie bar mass center displacement, **(c)** bogie bar mass center rotation.",
    ),
    Caption(
        "figure10",
        "Figure 10",
        f"Time series in Case 3. {_TIME_SERIES_FULL} (a) beam deflection at the rear mass, (b) bogie bar "
        "mass center displacement, (c) bogie bar mass center rotation.",
    ),
    Caption(
        "figure11",
        "Figure 11",
        f"Time series in Case 4. {_TIME_SERIES_FULL} (a) beam deflection at the rear mass, (b) bogie bar "
        "mass center displacement, (c) bogie bar mass center rotation.",
    ),
    Caption(
        "figure12",
        "Figure 12",
        f"Time series in Case 5. {_TIME_SERIES_FULL} **(a)** beam deflection at the rear mass, **(b)** "
        "bogie bar mass center displacement, **(c)** bogie bar mass center rotation.",
    ),
    Caption("figure13", "Figure 13", "Beam deflection at the rear mass in Case 5."),
    Caption(
        "figure14",
        "Figure 14",
        f"Time series in Case 6. {_TIME_SERIES_FULL} (a) beam deflection at the rear mass, (b) bogie bar "
        "mass center displacement, (c) bogie bar mass center rotation.",
    ),
    Caption("figure15", "Figure 15", "Beam deflection at the rear mass in Case 6."),
    Caption("figure16", "Figure 16", "Critical stiffness of the primary suspension using data from [48]."),
    Caption(
        "figureA1",
        "Figure A1",
        f"Time series in Case 7. {_TIME_SERIES_FULL} (a) beam deflection at the rear mass, (b) bogie bar "
        "mass center displacement, (c) bogie bar mass center rotation.",
    ),
    Caption(
        "figureA2",
        "Figure A2",
        "Time series in Cases 7-10. Case 7: violet; Case 8: green; Case 9: red; Case 10: blue. **(a)** beam "
        "deflection at the rear mass, **(b)** bogie bar mass center displacement, **(c)** bogie bar mass "
        "center rotation.",
        printed_label="Figure 2",
    ),
    Caption(
        "figureA3",
        "Figure A3",
        "Time series in Cases 7 and 11. Case 11: orange. (a) beam deflection at the rear mass, (b) bogie "
        "bar mass center displacement, (c) bogie bar mass center rotation.",
        printed_label="Figure A.3",
    ),
    Caption(
        "figureA4",
        "Figure A4",
        "Time series in Case 12. **(a)** beam deflection at the rear mass, **(b)** bogie bar mass center "
        "displacement, **(c)** bogie bar mass center rotation.",
    ),
    Caption(
        "figureA5",
        "Figure A5",
        "Time series in Case 12. **(a)** beam deflection at the rear mass, **(b)** bogie bar mass center "
        "displacement.",
    ),
    Caption(
        "figureA6",
        "Figure A6",
        "Time series in Case 13. **(a)** beam deflection at the rear mass, **(b)** bogie bar mass center "
        "displacement, **(c)** bogie bar mass center rotation.",
    ),
    Caption(
        "figureA7",
        "Figure A7",
        "Time series in Case 13. **(a)** beam deflection at the rear mass, **(b)** bogie bar mass center "
        "displacement.",
    ),
)
