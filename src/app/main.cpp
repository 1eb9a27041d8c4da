int main() { return 0; }  // placeholder (owner will replace)
