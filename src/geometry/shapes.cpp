// placeholder (owner will replace)
