"""rqt_plot: live plots of numeric fields of topics."""
