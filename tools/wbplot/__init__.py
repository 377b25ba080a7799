"""Figures and tables for the workbook: shared by tools/plot and tools/report."""
