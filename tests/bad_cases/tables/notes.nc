%PDF-1.4 not results
