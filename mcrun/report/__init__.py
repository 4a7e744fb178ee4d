"""Pictures and pages of a run: the plots (``plots``) and the self-contained HTML report
(``html``)."""
