"""The virtual bench's report: figures, interactive Plotly pages and the HTML that holds them
(:func:`tendonsheath.report.build.write`)."""

__all__: list[str] = []
