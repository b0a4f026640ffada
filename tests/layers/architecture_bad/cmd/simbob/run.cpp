// the command
int main() { return 0; }
