"""The trade-off study's figures (plot_tradeoff.py): tables read what adb-tradeoff wrote,
figures draw it."""
