"""The report of one analysis: the PDF that fits its response, and its JSON beside it.

An :class:`~isolator.analysis.Analysis` to which the paper applies (a 1-D block on one surface)
renders as the four-page report (:func:`isolator.report.pdf.write_report`: summary, record,
response, the harmonic regime map); any other (planar, multi-surface) as the three-page report
(:func:`isolator.report.pair.write_pair_report`: summary, ground motion, orbit).  Both JSON
files are :func:`isolator.report.summary.summary_dict` (the analysis schema, ``parameters`` and ``pdf``).
Rendering only: the model was chosen by the solver registry when the analysis ran.
"""

from __future__ import annotations


def write_analysis_report(analysis, pdf_path, *, command: str = "", parameters: list[dict] | None = None) -> dict:
    """Render ``analysis`` as a PDF and write its JSON beside it (same name, ``.json``); returns the JSON dict.

    Parameters
    ----------
    analysis : isolator.analysis.Analysis
        From :func:`isolator.analysis.analyse` (a 1-D analysis with ``map_resolution``).
    pdf_path : str or Path
        Output PDF [-].
    command : str
        The command line, printed in the report [-].
    parameters : list of dict, optional
        The review parameters the pages use (:func:`isolator.report.summary.report_parameters`; default: their
        defaults), printed and written in the JSON (``parameters``).
    """
    if not analysis.paper_applies:  # planar, or a bearing the paper's map does not describe
        from isolator.report.pair import write_pair_report

        return write_pair_report(analysis, pdf_path, command=command, parameters=parameters)
    from isolator.report.pdf import write_report

    return write_report(analysis, pdf_path, command=command, parameters=parameters)
