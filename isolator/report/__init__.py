"""The engineering-review report: analysis (summary.py), figures (figures.py), PDF (pdf.py).

``isolator.report.pdf.write_report(analysis, pdf_path)`` writes the multi-page PDF and
the JSON of the same numbers beside it (``NAME.json``), both atomically.
"""
